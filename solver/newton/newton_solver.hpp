#pragma once
// Projected Newton on one environment's incremental potential, one iteration at a time, as named
// stages: find contacts, assemble (pinned DOFs eliminated), solve, test convergence, filter the
// step (CCD, inversion, Armijo), commit. The solver holds what is reused from one iteration to
// the next (the potential's terms, the assembly pattern, the factorizations); the step under way
// is a NewtonStep, and the environment's state a State.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "solver/contact/candidates.hpp"
#include "solver/linear/linear_system_solver.hpp"
#include "solver/linear/sparse_assembly.hpp"
#include "solver/linear/sparse_cholesky.hpp"
#include "solver/model/model.hpp"
#include "solver/newton/diagnostics.hpp"
#include "solver/newton/failure.hpp"
#include "solver/newton/step_targets.hpp"
#include "solver/potential/incremental_potential.hpp"
#include "solver/scene/state.hpp"

namespace grip::solver {

// Where a step under way stands: its targets, how much of the prescribed motion is done, which
// friction lag and Newton iteration it is in, and the residual scale of the current solve.
struct NewtonStep {
  double h = 0.0;  // s, this step's length (dt, or a fraction of it when a step is retried)
  StepTargets targets;
  double progress = 0.0;
  int lag = 0;
  int iteration = 0;  // within the current lag's solve
  bool held = false;  // converged, held open (StepPolicy::freeze_converged off)
  // The residual's scale: the first residual of the current solve (negative until it is taken),
  // never less than the standard weight.
  double first_residual = -1.0;
  // The last Newton step was full and started from a residual within sqrt(newton_tol) of the
  // scale: quadratic convergence expects this iteration to converge (NewtonSolver::iterate).
  bool convergence_expected = false;
  // N: the dynamic bodies' weight under standard gravity (9.81 m/s^2), whatever the scene's
  // gravity, so that the convergence test asks the same force accuracy with gravity on or off.
  double standard_weight = 0.0;
  Eigen::VectorXd gradient;
  Eigen::VectorXd kinematic_force;
  // The DOFs eliminated from the system (prescribed or held): the assembly leaves out their
  // rows and columns.
  std::vector<char> fixed;
  // Every pair within d_hat of the current positions, once found (within_reach): after a line
  // search, the pairs that can come within d_hat anywhere on the path the step was taken along,
  // so at the accepted point too. It spares a broad phase per iteration; the
  // environment hands it on to the next step, which starts where this one ends.
  std::optional<std::vector<ContactCandidate>> near;
};

class NewtonSolver {
 public:
  enum class Outcome { kContinue, kConverged, kFailed };

  explicit NewtonSolver(const Model& model);

  // Systems of at least `min_dofs` rows are solved by `solver` instead of the own Cholesky.
  void use_linear_solver(std::shared_ptr<LinearSystemSolver> solver, int min_dofs);

  // The step's constants: its inertia target under `state`'s gravity (and the standard weight
  // of its dynamic bodies), the potential's start positions and kappa, and the first friction lag.
  void begin_step(const State& state, const Vertices& start, NewtonStep& step,
                  bool friction_at_zero_mu);
  // A further friction lag at the step's current positions; the next solve starts afresh.
  void lag_friction(const State& state, NewtonStep& step, bool friction_at_zero_mu);

  // Why an iteration failed: the code, and a message for people.
  struct FailureReport {
    Failure code = Failure::kNone;
    std::string message;
  };

  // One Newton iteration from state.q. kFailed fills `failure`.
  Outcome iterate(State& state, NewtonStep& step, StepDiagnostics& diagnostics,
                  FailureReport& failure);

  const IncrementalPotential& potential() const { return potential_; }
  // A step taken elsewhere (Environment::adopt_step): the contacts its potential ended with
  // (IncrementalPotential::adopt_contacts) and the CG iterations its solves took.
  void adopt_step(Vertices start_positions, double kappa, double h,
                  std::vector<FrictionContact> friction, long cg_iterations);

  // The broad phase this solver keeps; its owner's queries between steps may use it too.
  ContactBroadPhase& broad_phase() { return broad_phase_; }

  // step.near, found first if need be; `x` are the current collision positions.
  const std::vector<ContactCandidate>& near(NewtonStep& step, const Vertices& x);

  // Where this solver's time went; callers may time their own stages into it.
  StageSeconds& stages() { return stages_; }
  const StageSeconds& stages() const { return stages_; }
  // How its Newton systems were solved.
  const LinearSolveCounts& linear_solves() const { return linear_solves_; }

 private:
  // The Newton system at the current iterate, pinned DOFs eliminated:
  // H_ff p_f = -(g_f + H_fp lift_p + H_fk dk), p_p = lift_p.
  struct System {
    explicit System(std::vector<Eigen::Triplet<double>>& buffer) : triplets(buffer) {}
    // The Hessian's lower-triangle triplets: the calling thread's buffer (hessian_triplets()).
    std::vector<Eigen::Triplet<double>>& triplets;
    Vertices x;  // collision vertices now
    Eigen::VectorXd rhs;
    double residual = 0.0;  // largest |g| over the free DOFs
    bool moving = false;    // prescribed motion still to come
    bool projected = true;  // contact Hessians projected to PSD one by one
  };
  LinearSystemSolver& linear_solver();
  bool assemble(const State& state, NewtonStep& step, System& system, bool project_contacts,
                FailureReport& failure);
  void eliminate_prescribed(const State& state, NewtonStep& step, System& system) const;
  bool solve(const State& state, NewtonStep& step, System& system, Eigen::VectorXd& p,
             FailureReport& failure);
  bool solve_by_earlier_factorization(const Eigen::SparseMatrix<double>& matrix,
                                      const Eigen::VectorXd& rhs, Eigen::VectorXd& p);
  bool residual_converged(const NewtonStep& step, const System& system) const;
  bool converged_by_gradient(const State& state, NewtonStep& step, StepDiagnostics& diagnostics);
  double free_residual(const NewtonStep& step) const;
  bool step_converged(const NewtonStep& step, const System& system, const Eigen::VectorXd& p) const;
  bool filter_step(const State& state, NewtonStep& step, const System& system,
                   const Eigen::VectorXd& p, double& alpha, StepDiagnostics& diagnostics,
                   FailureReport& failure);
  static void commit(State& state, NewtonStep& step, const Eigen::VectorXd& p, double alpha);

  const Model& model_;
  IncrementalPotential potential_;
  ContactBroadPhase broad_phase_;
  SparseAssembly assembly_;
  SparseCholesky cholesky_;
  std::shared_ptr<LinearSystemSolver> linear_solver_;  // null: cholesky_ solves every system
  int linear_solver_min_dofs_ = 0;
  StageSeconds stages_;
  LinearSolveCounts linear_solves_;
};

}  // namespace grip::solver
