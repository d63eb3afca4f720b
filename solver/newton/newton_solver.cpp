#include "solver/newton/newton_solver.hpp"

#include <cmath>

#include "solver/contact/candidates.hpp"
#include "solver/newton/line_search.hpp"
#include "solver/potential/friction_lag.hpp"

namespace grip::solver {
namespace {

// The Hessian's triplets are rebuilt in every Newton iteration and used only within it, so one
// buffer per thread serves every environment the thread iterates: a batch keeps all its
// environments' steps under way at once, and a buffer each cost about 17 MB per fin-ray
// environment. Nothing inside an iteration runs other tasks on the thread (no nested TBB).
std::vector<Eigen::Triplet<double>>& hessian_triplets() {
  thread_local std::vector<Eigen::Triplet<double>> triplets;
  return triplets;
}

// The default gravity's magnitude (SimParameters::gravity), the scale of the residual.
constexpr double kStandardGravity = 9.81;  // m/s^2

// The largest displacement of any vertex under the DOF change dq (m).
double max_vertex_displacement(const Model& model, const Eigen::VectorXd& dq) {
  double largest = 0.0;
  for (const BodyModel& body : model.bodies()) {
    largest = std::max(largest, body.kind->max_displacement(body.local, dq));
  }
  return largest;
}

}  // namespace

NewtonSolver::NewtonSolver(const Model& model)
    : model_(model), potential_(model), cholesky_(model.ordering()) {}

void NewtonSolver::use_linear_solver(std::shared_ptr<LinearSystemSolver> solver, int min_dofs) {
  linear_solver_ = std::move(solver);
  linear_solver_min_dofs_ = min_dofs;
}

void NewtonSolver::begin_step(const State& state, const Vertices& start, NewtonStep& step,
                              bool friction_at_zero_mu) {
  // The inertia target: x_tilde = x + h v + h^2 M^-1 f_gravity.
  const double h = step.h;
  Eigen::VectorXd q_tilde = state.q + h * state.v;
  for (const BodyModel& body : model_.bodies()) {
    body.kind->add_gravity(body.local, state.gravity, h, q_tilde);
    step.standard_weight += body.kind->mass(body.local) * kStandardGravity;
  }
  // Driven bodies: their DOFs at their scripts' poses at the end of the step.
  Eigen::VectorXd q_drive = state.q;
  for (std::size_t b = 0; b < model_.bodies().size(); ++b) {
    const BodyModel& body = model_.bodies()[b];
    body.kind->set_drive_target(body.local, step.targets.pose_target[b], q_drive);
  }
  potential_.begin_step(state.q, q_tilde, std::move(q_drive), start, state.kappa, h);
  const std::vector<ContactCandidate>& candidates = near(step, start);
  const StageTimer timer(stages_.friction_lag);
  potential_.set_friction(
      solver::lag_friction(potential_.barrier(), start, candidates, friction_at_zero_mu));
}

const std::vector<ContactCandidate>& NewtonSolver::near(NewtonStep& step, const Vertices& x) {
  if (!step.near) {
    const StageTimer timer(stages_.broad_phase);
    step.near = broad_phase_.near(model_.collision(), x, x, model_.sim().d_hat);
  }
  return *step.near;
}

void NewtonSolver::lag_friction(const State& state, NewtonStep& step, bool friction_at_zero_mu) {
  step.iteration = 0;
  step.first_residual = -1.0;
  step.convergence_expected = false;
  const Vertices x = collision_positions(model_, state.q, step.targets, step.progress);
  const std::vector<ContactCandidate>& candidates = near(step, x);
  const StageTimer timer(stages_.friction_lag);
  potential_.set_friction(
      solver::lag_friction(potential_.barrier(), x, candidates, friction_at_zero_mu));
}

void NewtonSolver::adopt_step(Vertices start_positions, double kappa, double h,
                              std::vector<FrictionContact> friction, long cg_iterations) {
  potential_.adopt_contacts(std::move(start_positions), kappa, h, std::move(friction));
  linear_solves_.cg_iterations += cg_iterations;
}

NewtonSolver::Outcome NewtonSolver::iterate(State& state, NewtonStep& step,
                                            StepDiagnostics& diagnostics, FailureReport& failure) {
  ++step.iteration;
  if (step.convergence_expected && converged_by_gradient(state, step, diagnostics)) {
    return Outcome::kConverged;
  }
  System system(hessian_triplets());
  const bool project =
      step.iteration <= model_.sim().projected_iterations || !linear_solver().refuses_indefinite();
  if (!assemble(state, step, system, project, failure)) {
    return Outcome::kFailed;
  }
  // The residual's scale: this solve's first residual, and never less than the dynamic bodies'
  // standard weight, so that neither a body resting in equilibrium nor a step with gravity off
  // whose first residual is nearly zero (nothing has moved yet) is asked for round-off.
  const double h = step.h;
  if (step.first_residual < 0.0) {
    step.first_residual = std::max(system.residual, step.standard_weight * h * h);
  }
  diagnostics.residual = system.residual / (h * h);
  // A residual already small enough needs no Newton step: the step's last iteration factorizes
  // nothing.
  if (residual_converged(step, system)) return Outcome::kConverged;
  Eigen::VectorXd p;
  if (!solve(state, step, system, p, failure)) return Outcome::kFailed;
  if (step_converged(step, system, p)) return Outcome::kConverged;
  double alpha = 1.0;
  if (!filter_step(state, step, system, p, alpha, diagnostics, failure)) return Outcome::kFailed;
  commit(state, step, p, alpha);
  step.convergence_expected =
      alpha >= 1.0 && !system.moving && !step.held &&
      system.residual <= std::sqrt(model_.sim().newton_tol) * step.first_residual;
  return Outcome::kContinue;
}

LinearSystemSolver& NewtonSolver::linear_solver() {
  if (linear_solver_ && model_.dof_count() >= linear_solver_min_dofs_) return *linear_solver_;
  return cholesky_;
}

bool NewtonSolver::assemble(const State& state, NewtonStep& step, System& system,
                            bool project_contacts, FailureReport& failure) {
  system.x = collision_positions(model_, state.q, step.targets, step.progress);
  const std::vector<ContactCandidate>& candidates = near(step, system.x);
  system.moving = step.progress < 1.0;
  const Vertices kinematic_motion =
      collision_positions(model_, state.q, step.targets, 1.0) - system.x;
  system.projected = project_contacts;
  {
    const StageTimer timer(stages_.derivatives);
    potential_.derivatives(state.q, system.x, candidates, step.gradient, system.triplets,
                           system.moving ? &kinematic_motion : nullptr, &step.kinematic_force,
                           project_contacts);
  }
  if (!step.gradient.allFinite()) {
    failure = {Failure::kNonFinite, "non-finite gradient in Newton iteration"};
    return false;
  }
  const StageTimer timer(stages_.assembly);
  eliminate_prescribed(state, step, system);
  return true;
}

void NewtonSolver::eliminate_prescribed(const State& state, NewtonStep& step,
                                        System& system) const {
  const int n = model_.dof_count();
  const std::vector<char>& prescribed = model_.prescribed();
  // Held DOFs (Environment::hold) are prescribed to stay where they are.
  const std::vector<char>& held = state.held;
  step.fixed.resize(n);
  for (int i = 0; i < n; ++i) step.fixed[i] = prescribed[i] || (!held.empty() && held[i]);
  // The prescribed DOFs' motion still to come.
  Eigen::VectorXd lift = Eigen::VectorXd::Zero(n);
  system.rhs = -step.gradient - step.kinematic_force;
  if (system.moving) {
    for (int i = 0; i < n; ++i) {
      if (prescribed[i]) lift[i] = step.targets.prescribed_target[i] - state.q[i];
    }
    for (const auto& e : system.triplets) {
      const int r = static_cast<int>(e.row()), c = static_cast<int>(e.col());
      system.rhs[r] -= e.value() * lift[c];
      if (r != c) system.rhs[c] -= e.value() * lift[r];
    }
  }
  for (int i = 0; i < n; ++i) {
    if (step.fixed[i]) system.rhs[i] = lift[i];
  }
  system.residual = free_residual(step);
}

// The largest |g| over the free DOFs.
double NewtonSolver::free_residual(const NewtonStep& step) const {
  double residual = 0.0;
  for (Eigen::Index i = 0; i < step.gradient.size(); ++i) {
    if (!step.fixed[i]) residual = std::max(residual, std::abs(step.gradient[i]));
  }
  return residual;
}

bool NewtonSolver::solve(const State& state, NewtonStep& step, System& system, Eigen::VectorXd& p,
                         FailureReport& failure) {
  const int n = model_.dof_count();
  LinearSystemSolver& solver = linear_solver();
  const auto assembled = [&]() -> const Eigen::SparseMatrix<double>& {
    const StageTimer timer(stages_.assembly);
    return assembly_.assemble(n, system.triplets, step.fixed);
  };
  const Eigen::SparseMatrix<double>* matrix = &assembled();
  // A projected matrix is positive definite, so CG may solve it.
  if (&solver == &cholesky_ && system.projected &&
      solve_by_earlier_factorization(*matrix, system.rhs, p)) {
    return true;
  }
  // Exact contact Hessians whose sum is not positive definite are projected one by one.
  const auto factorize = [&] {
    const StageTimer timer(stages_.factorization);
    ++linear_solves_.factorizations;
    return solver.factorize(*matrix);
  };
  bool factorized = factorize();
  if (!factorized && !system.projected) {
    if (!assemble(state, step, system, true, failure)) return false;
    matrix = &assembled();
    factorized = factorize();
  }
  bool solved = false;
  if (factorized) {
    const StageTimer timer(stages_.solve);
    solved = solver.solve(system.rhs, p);
  }
  if (!solved) {
    failure = {Failure::kLinearSolve, "Newton system not solved: " + solver.failure()};
    return false;
  }
  if (!p.allFinite()) {
    failure = {Failure::kNonFinite, "non-finite Newton step"};
    return false;
  }
  return true;
}

// CG on the last factorization (SimParameters::reuse_iterations, reuse_tolerance). Tried only
// where its most iterations cost fewer flops than the factorization they spare: each is a pair
// of triangular solves with the factor and a product with the matrix (4 flops per stored entry
// of each). That leaves out small systems (rigid jaws, the rigid hand), and counting flops, not
// seconds, keeps the choice, and so the trajectory, the same on any machine.
bool NewtonSolver::solve_by_earlier_factorization(const Eigen::SparseMatrix<double>& matrix,
                                                  const Eigen::VectorXd& rhs, Eigen::VectorXd& p) {
  const int max_iterations = model_.sim().reuse_iterations;
  const double iteration_flops =
      4.0 * static_cast<double>(cholesky_.factor_entries() + matrix.nonZeros());
  if (max_iterations == 0 || cholesky_.factor_flops() < max_iterations * iteration_flops) {
    return false;
  }
  const StageTimer timer(stages_.solve);
  int iterations = 0;
  const bool solved = cholesky_.solve_preconditioned(matrix, rhs, model_.sim().reuse_tolerance,
                                                     max_iterations, p, iterations);
  linear_solves_.cg_iterations += iterations;
  if (!solved || !p.allFinite()) return false;
  ++linear_solves_.reused;
  return true;
}

// Converged: the residual fell by newton_tol against its scale (residual_converged), or the
// step would change no vertex's velocity by more than newton_velocity_tol (step_converged). A
// test on the step's length alone is not enough: near d_hat the barrier (and sticking friction)
// is so stiff that a micrometre off leaves the normal force, and friction's lagged lambda, wrong.
// Neither while prescribed motion is still to come, nor in a step held open.
bool NewtonSolver::residual_converged(const NewtonStep& step, const System& system) const {
  if (system.moving || step.held) return false;
  return system.residual <= model_.sim().newton_tol * step.first_residual;
}

// Near a solution Newton's residual falls quadratically, so most steps' last iteration only finds
// the residual small enough: expected (NewtonStep::convergence_expected), the test takes the
// gradient alone, and the Hessian is evaluated (with the gradient again, the same to the bit)
// only if the residual is not small enough after all.
bool NewtonSolver::converged_by_gradient(const State& state, NewtonStep& step,
                                         StepDiagnostics& diagnostics) {
  const Vertices x = collision_positions(model_, state.q, step.targets, step.progress);
  const std::vector<ContactCandidate>& candidates = near(step, x);
  {
    const StageTimer timer(stages_.derivatives);
    potential_.gradient(state.q, x, candidates, step.gradient);
  }
  // A non-finite gradient is left to the full evaluation, which reports it.
  if (!step.gradient.allFinite()) return false;
  const double residual = free_residual(step);
  diagnostics.residual = residual / (step.h * step.h);
  return residual <= model_.sim().newton_tol * step.first_residual;
}

bool NewtonSolver::step_converged(const NewtonStep& step, const System& system,
                                  const Eigen::VectorXd& p) const {
  if (system.moving || step.held) return false;
  return max_vertex_displacement(model_, p) <= model_.sim().newton_velocity_tol * step.h;
}

// CCD's safe fraction of the step, then positive volumes, then (once the prescribed motion is
// done) Armijo on the incremental potential. On success the pairs within reach on the path become
// step.near.
bool NewtonSolver::filter_step(const State& state, NewtonStep& step, const System& system,
                               const Eigen::VectorXd& p, double& alpha,
                               StepDiagnostics& diagnostics, FailureReport& failure) {
  const SimParameters& sim = model_.sim();
  const Vertices x_end = collision_positions(model_, state.q + p, step.targets, 1.0);
  // The barrier acts only on the pairs that can come within d_hat on the path; CCD watches those
  // and the far pairs it could stop at (within_reach).
  std::vector<ContactCandidate> reachable, watched;
  {
    const StageTimer timer(stages_.broad_phase);
    reachable = broad_phase_.near(model_.collision(), system.x, x_end, sim.d_hat, &watched,
                                  sim.ccd_rescaling);
  }
  {
    const StageTimer timer(stages_.ccd);
    alpha = collision_free_fraction(watched, system.x, x_end, sim.ccd_rescaling);
  }
  if (!(alpha > 0.0)) {
    failure = {Failure::kCcdNoMotion, "continuous collision detection allows no motion"};
    return false;
  }
  const StageTimer timer(stages_.line_search);
  if (!halve_until_no_inversion(model_, state.q, p, alpha, diagnostics.line_search_steps)) {
    failure = {Failure::kInversion, "no step keeps every tetrahedron positively oriented"};
    return false;
  }
  if (!system.moving) {
    const double energy = potential_.energy(state.q, system.x, reachable);
    if (!armijo(potential_, model_, step.targets, reachable, state.q, p, energy,
                step.gradient.dot(p), step.held, alpha, diagnostics.line_search_steps)) {
      failure = {Failure::kLineSearch, "line search cannot decrease the incremental potential"};
      return false;
    }
  }
  step.near = std::move(reachable);  // the step is taken along this path
  return true;
}

void NewtonSolver::commit(State& state, NewtonStep& step, const Eigen::VectorXd& p, double alpha) {
  state.q += alpha * p;
  step.progress = alpha >= 1.0 ? 1.0 : step.progress + alpha * (1.0 - step.progress);
}

}  // namespace grip::solver
