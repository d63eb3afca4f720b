#pragma once
// The IPC solver's settings (solver::SimParameters) as one parameter table: a scene file's
// [sim] table and a job file's [physics] table read them, grip trial offers them as options, a
// dataset's provenance lists them and the docs' tables are made from them (docs/scene-format.md).
#include "solver/scene/scene.hpp"
#include "src/config/config.hpp"
#include "src/config/parameter.hpp"

namespace grip::scene {

// Every setting but gravity (a scene's own key; a trial's gravity is the protocol's).
config::ParameterTable<solver::SimParameters> sim_parameter_table();

// Overwrites the settings the table gives (kappa = "auto" turns adaptive kappa on) and keeps
// the rest. Throws config::ConfigError at the key for a value out of range.
void read_sim_parameters(const config::Table& table, solver::SimParameters& parameters);

}  // namespace grip::scene
