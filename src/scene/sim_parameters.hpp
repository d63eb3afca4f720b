#pragma once
// The solver settings shared by scene files' [sim] table and job files' [physics] table, read
// strictly with their range checks (docs/scene-format.md lists them).
#include "solver/scene/scene.hpp"
#include "src/config/config.hpp"

namespace grip::scene {

// The keys read_sim_parameters reads; a table may allow more of its own.
inline const std::initializer_list<std::string_view> kSimParameterKeys = {"dt",
                                                                          "d_hat",
                                                                          "kappa",
                                                                          "eps_v",
                                                                          "newton_tol",
                                                                          "newton_velocity_tol",
                                                                          "max_newton_iters",
                                                                          "projected_iterations",
                                                                          "max_step_halvings",
                                                                          "friction_lag_iterations",
                                                                          "reuse_iterations",
                                                                          "reuse_tolerance",
                                                                          "ccd_rescaling"};

// Overwrites the settings the table gives (kappa = "auto" turns adaptive kappa on) and keeps
// the rest. Throws config::ConfigError at the key for a value out of range.
void read_sim_parameters(const config::Table& table, solver::SimParameters& parameters);

}  // namespace grip::scene
