#include "src/scene/sim_parameters.hpp"

namespace grip::scene {
namespace {

double positive(const config::Table& table, std::string_view key, double fallback) {
  const double value = table.number_or(key, fallback);
  if (!(value > 0)) table.fail(key, "must be positive");
  return value;
}

}  // namespace

void read_sim_parameters(const config::Table& table, solver::SimParameters& p) {
  p.dt = positive(table, "dt", p.dt);
  p.d_hat = positive(table, "d_hat", p.d_hat);
  if (table.is_string("kappa")) {
    table.choice("kappa", {"auto"});
    p.adaptive_kappa = true;
  } else {
    p.kappa = positive(table, "kappa", p.kappa);
  }
  p.eps_v = positive(table, "eps_v", p.eps_v);
  p.newton_tol = positive(table, "newton_tol", p.newton_tol);
  p.newton_velocity_tol = positive(table, "newton_velocity_tol", p.newton_velocity_tol);
  // Bounds that keep a value meaningful and its int from wrapping: each Newton iteration is a
  // factorization, each lag iteration a whole Newton solve.
  p.max_newton_iters = table.count_or("max_newton_iters", p.max_newton_iters, 1, 100'000);
  p.projected_iterations =
      table.count_or("projected_iterations", p.projected_iterations, 0, 100'000);
  p.max_step_halvings = table.count_or("max_step_halvings", p.max_step_halvings, 0, 20);
  p.friction_lag_iterations =
      table.count_or("friction_lag_iterations", p.friction_lag_iterations, 1, 100);
  p.reuse_iterations = table.count_or("reuse_iterations", p.reuse_iterations, 0, 1000);
  p.reuse_tolerance = table.number_or("reuse_tolerance", p.reuse_tolerance);
  if (!(p.reuse_tolerance > 0 && p.reuse_tolerance < 1)) {
    table.fail("reuse_tolerance", "must lie strictly between 0 and 1");
  }
  p.ccd_rescaling = table.number_or("ccd_rescaling", p.ccd_rescaling);
  if (!(p.ccd_rescaling > 0 && p.ccd_rescaling < 1)) {
    table.fail("ccd_rescaling", "must lie strictly between 0 and 1");
  }
}

}  // namespace grip::scene
