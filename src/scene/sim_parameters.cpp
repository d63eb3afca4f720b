#include "src/scene/sim_parameters.hpp"

#include <array>

#include "src/config/parameter_table.hpp"

namespace grip::scene {
namespace {

using config::Range;
using P = config::Parameter<solver::SimParameters>;
using S = solver::SimParameters;

// Bounds that keep a value meaningful and its int from wrapping: each Newton iteration is a
// factorization, each lag iteration a whole Newton solve.
constexpr std::array kSimParameters = {
    P{.key = "dt",
      .real = &S::dt,
      .range = Range::positive(),
      .unit = "s",
      .doc = "time step, implicit Euler"},
    P{.key = "d_hat",
      .real = &S::d_hat,
      .range = Range::positive(),
      .unit = "m",
      .doc = "barrier activation distance"},
    P{.key = "kappa",
      .real = &S::kappa,
      .range = Range::positive(),
      .unit = "N/m",
      .doc = "barrier stiffness; \"auto\": start at the default and double it whenever a step ends "
             "with a contact closer than d_hat / 10",
      .automatic = &S::adaptive_kappa},
    P{.key = "eps_v",
      .real = &S::eps_v,
      .range = Range::positive(),
      .unit = "m/s",
      .doc = "friction's static-to-dynamic velocity"},
    P{.key = "newton_tol",
      .real = &S::newton_tol,
      .range = Range::positive(),
      .doc = "relative Newton tolerance: converged when the largest free-DOF gradient entry falls "
             "below this times its value at the solve's first iteration (never below this times "
             "the dynamic bodies' weight times dt^2)"},
    P{.key = "newton_velocity_tol",
      .real = &S::newton_velocity_tol,
      .range = Range::positive(),
      .unit = "m/s",
      .doc = "also converged when the Newton step would change no vertex's velocity by more than "
             "this"},
    P{.key = "max_newton_iters",
      .count = &S::max_newton_iters,
      .range = Range::from_to(1, 100'000),
      .doc = "past this the step (or part of it) is retried in halves, then fails with the "
             "reason"},
    P{.key = "projected_iterations",
      .count = &S::projected_iterations,
      .range = Range::from_to(0, 100'000),
      .doc = "Newton iterations with every contact Hessian projected to PSD; after these, the "
             "exact ones where their sum is positive definite (docs/simulation.md)"},
    P{.key = "max_step_halvings",
      .count = &S::max_step_halvings,
      .range = Range::from_to(0, 20),
      .doc = "how deep a failed step is retried as two half steps (dt / 2^k) before the "
             "environment fails"},
    P{.key = "friction_lag_iterations",
      .count = &S::friction_lag_iterations,
      .range = Range::from_to(1, 100),
      .doc = "times a step is solved with friction lagged at the newest solution"},
    P{.key = "reuse_iterations",
      .count = &S::reuse_iterations,
      .range = Range::from_to(0, 1000),
      .doc = "a positive-definite Newton system is first solved by CG preconditioned with the last "
             "factorization, at most this many iterations, and factorized afresh only if they fall "
             "short (docs/simulation.md, item 3); 0 factorizes every system"},
    P{.key = "reuse_tolerance",
      .real = &S::reuse_tolerance,
      .range = Range::strictly_between(0, 1),
      .doc = "the relative residual those CG solves must reach (of the Newton system H p = b)"},
    P{.key = "ccd_rescaling",
      .real = &S::ccd_rescaling,
      .range = Range::strictly_between(0, 1),
      .doc = "additive CCD keeps at least this fraction of each gap per line search step"},
};

}  // namespace

config::ParameterTable<solver::SimParameters> sim_parameter_table() { return kSimParameters; }

void read_sim_parameters(const config::Table& table, solver::SimParameters& parameters) {
  config::read_parameters(table, sim_parameter_table(), parameters);
}

}  // namespace grip::scene
