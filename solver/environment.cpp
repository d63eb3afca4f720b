#include "solver/environment.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <utility>

#include "solver/contact/candidates.hpp"
#include "solver/linear/blas_threads.hpp"

namespace grip::solver {

Environment::Environment(std::shared_ptr<const Model> model)
    : model_(std::move(model)), newton_(*model_) {
  // Environments run side by side on threads of their own (solver/batch); a BLAS threading
  // inside each factorization would oversubscribe the cores.
  static std::once_flag blas_configured;
  std::call_once(blas_configured, use_single_threaded_blas);
  const SceneDescription& scene = model_->scene();
  const std::size_t body_count = scene.bodies.size();
  state_.q.setZero(model_->dof_count());
  state_.v.setZero(model_->dof_count());
  state_.poses.resize(body_count);
  state_.scripts.resize(body_count);
  state_.kinematic_velocity.resize(body_count);
  state_.gravity = model_->sim().gravity;
  state_.kappa = model_->sim().kappa;
  for (std::size_t b = 0; b < body_count; ++b) {
    const BodyDescription& description = scene.bodies[b];
    state_.poses[b] = description.pose;
    state_.scripts[b] = description.script;
    state_.kinematic_velocity[b] = description.script.keyframes.empty()
                                       ? description.script.velocity
                                       : Eigen::Vector3d::Zero();
    const BodyModel& body = model_->bodies()[b];
    body.kind->initial_state(body.local, description, state_);
  }
}

Environment::~Environment() = default;
Environment::Environment(Environment&&) noexcept = default;

void Environment::place(int index, const Eigen::Isometry3d& motion) {
  if (state_.time != 0.0 || step_) {
    throw std::logic_error("Environment::place after the first step");
  }
  const BodyModel& body = model_->bodies().at(static_cast<std::size_t>(index));
  body.kind->place(body.local, motion, state_);
  near_.reset();
}

void Environment::set_script(int body, const Script& script) {
  state_.scripts.at(static_cast<std::size_t>(body)) = script;
}

void Environment::hold(int index) {
  const BodyModel& body = model_->bodies().at(static_cast<std::size_t>(index));
  if (!body.has_dofs()) {
    throw std::invalid_argument("Environment::hold: body '" + body.name + "' is kinematic");
  }
  const std::vector<int> dofs = body.kind->held_dofs(body.local, state_);
  if (state_.held.empty()) state_.held.assign(static_cast<std::size_t>(model_->dof_count()), 0);
  for (int d : dofs) {
    state_.held[static_cast<std::size_t>(d)] = 1;
    state_.v[d] = 0.0;
  }
}

void Environment::release(int index) {
  const BodyModel& body = model_->bodies().at(static_cast<std::size_t>(index));
  if (state_.held.empty()) return;
  std::fill_n(state_.held.begin() + body.dof_offset, body.dof_count, 0);
  if (std::none_of(state_.held.begin(), state_.held.end(), [](char h) { return h != 0; })) {
    state_.held.clear();
  }
}

void Environment::use_linear_solver(std::shared_ptr<LinearSystemSolver> solver, int min_dofs) {
  newton_.use_linear_solver(std::move(solver), min_dofs);
}

Environment::Progress Environment::fail(Failure code, const std::string& reason) {
  failure_code_ = code;
  if (step_) statistics_.count_step(diagnostics_.newton_iterations);
  failure_ = "t = " + std::to_string(state_.time) + " s: " + reason;
  step_.reset();
  return Progress::kFailed;
}

bool Environment::step() {
  Progress progress = begin_step();
  while (progress == Progress::kIterating) progress = iterate();
  if (progress == Progress::kConverged) progress = finish_held_step();
  return progress == Progress::kStepDone;
}

Environment::Progress Environment::begin_step() {
  if (failed()) return Progress::kFailed;
  if (step_) throw std::logic_error("Environment::begin_step while a step is under way");
  diagnostics_ = StepDiagnostics{};
  diagnostics_.kappa = state_.kappa;
  plan_.end_time = state_.time + model_->sim().dt;
  plan_.halvings = 0;
  if (state_.time == 0.0 && !check_start()) return Progress::kFailed;
  return begin_part();
}

bool Environment::check_start() {
  const StepTargets now = targets_at_rest(*model_, state_);
  const Vertices start = solver::collision_positions(*model_, state_.q, now, 0.0);
  near_ = newton_.broad_phase().find(model_->collision(), start, start, model_->sim().d_hat);
  for (const ContactCandidate& c : *near_) {
    if (!(newton_.potential().barrier().contact_force(c, start).distance > 0.0)) {
      fail(Failure::kIntersectingStart,
           "intersecting start: two surfaces touch or cross before the first step");
      return false;
    }
  }
  return true;
}

void Environment::adopt_step(AdoptedStep step) {
  if (step_ || failed()) {
    throw std::logic_error("Environment::adopt_step while a step is under way or after failing");
  }
  state_ = std::move(step.state);
  diagnostics_ = std::move(step.diagnostics);
  near_.reset();
  newton_.adopt_step(std::move(step.start_positions), step.kappa, step.h, std::move(step.friction),
                     step.cg_iterations);
  const int iterations = diagnostics_.newton_iterations;
  statistics_.newton_iterations += iterations;
  statistics_.max_step_iterations = std::max(statistics_.max_step_iterations, iterations);
  statistics_.retries += diagnostics_.retries;
  statistics_.count_step(iterations);
  if (step.failure != Failure::kNone) {
    failure_code_ = step.failure;
    failure_ = std::move(step.message);
    return;
  }
  ++statistics_.steps;
}

Environment::Progress Environment::begin_part() {
  plan_.part_start = state_;
  step_ = std::make_unique<NewtonStep>();
  step_->h = std::ldexp(model_->sim().dt, -plan_.halvings);
  step_->targets = step_targets(*model_, state_, step_->h);
  step_->near = std::exchange(near_, std::nullopt);
  const Vertices start = solver::collision_positions(*model_, state_.q, step_->targets, 0.0);
  newton_.begin_step(state_, start, *step_, policy_.friction_terms_at_zero_mu);
  return Progress::kIterating;
}

Environment::Progress Environment::iterate() {
  if (failed()) return Progress::kFailed;
  if (!step_) throw std::logic_error("Environment::iterate without begin_step");
  NewtonStep& step = *step_;
  const int limit = model_->sim().max_newton_iters;
  if (step.iteration == limit && !step.held) {
    return retry_or_fail({Failure::kNewtonLimit,
                          "Newton did not converge in " + std::to_string(limit) + " iterations"});
  }
  ++diagnostics_.newton_iterations;
  ++statistics_.newton_iterations;
  statistics_.max_step_iterations =
      std::max(statistics_.max_step_iterations, diagnostics_.newton_iterations);
  NewtonSolver::FailureReport failure;
  switch (newton_.iterate(state_, step, diagnostics_, failure)) {
    case NewtonSolver::Outcome::kFailed:
      return retry_or_fail(failure);
    case NewtonSolver::Outcome::kContinue:
      return step.held ? Progress::kConverged : Progress::kIterating;
    case NewtonSolver::Outcome::kConverged:
      break;
  }
  // Each further friction lag re-linearizes friction at the current positions and solves again.
  if (++step.lag < std::max(1, model_->sim().friction_lag_iterations)) {
    newton_.lag_friction(state_, step, policy_.friction_terms_at_zero_mu);
    return Progress::kIterating;
  }
  return finish_converged_part();
}

// Rolls the failed part back and retries it as two halves, or fails the environment when the
// parts are already as short as max_step_halvings allows.
Environment::Progress Environment::retry_or_fail(const NewtonSolver::FailureReport& failure) {
  if (plan_.halvings >= model_->sim().max_step_halvings) {
    const std::string depth =
        plan_.halvings > 0 ? " (after " + std::to_string(plan_.halvings) + " halvings of dt)" : "";
    return fail(failure.code, failure.message + depth);
  }
  state_ = plan_.part_start;
  near_.reset();
  ++plan_.halvings;
  ++diagnostics_.retries;
  ++statistics_.retries;
  return begin_part();
}

Environment::Progress Environment::finish_converged_part() {
  const bool last_part = state_.time + 1.5 * step_->h >= plan_.end_time;
  if (!last_part) {
    finish_part();
    return begin_part();
  }
  if (!policy_.freeze_converged) {
    step_->held = true;
    return Progress::kConverged;
  }
  finish_step();
  return Progress::kStepDone;
}

Environment::Progress Environment::finish_held_step() {
  if (!step_ || !step_->held) throw std::logic_error("Environment::finish_held_step: none held");
  finish_step();
  return Progress::kStepDone;
}

void Environment::finish_part() {
  if (step_->near) near_ = std::exchange(step_->near, std::nullopt);
  const StepTargets& targets = step_->targets;
  const double h = step_->h;
  state_.v = (state_.q - targets.q_start) / h;
  for (std::size_t b = 0; b < model_->bodies().size(); ++b) {
    if (!model_->bodies()[b].scripted()) continue;
    state_.kinematic_velocity[b] = (targets.pose_target[b].position - state_.poses[b].position) / h;
    state_.poses[b] = targets.pose_target[b];
  }
  state_.time += h;
}

void Environment::finish_step() {
  const SimParameters& sim = model_->sim();
  finish_part();
  // Parts of a retried step add up to dt; the clock says so without their round-off.
  if (plan_.halvings > 0) state_.time = plan_.end_time;
  record_diagnostics();
  if (sim.adaptive_kappa && diagnostics_.min_distance < 0.1 * sim.d_hat) state_.kappa *= 2.0;
  ++statistics_.steps;
  statistics_.count_step(diagnostics_.newton_iterations);
  step_.reset();
}

void Environment::record_diagnostics() {
  const StageTimer timer(newton_.stages().diagnostics);
  const Vertices x = solver::collision_positions(*model_, state_.q, step_->targets, 1.0);
  if (!near_) near_ = newton_.broad_phase().find(model_->collision(), x, x, model_->sim().d_hat);
  diagnostics_.min_volume_ratio = min_volume_ratio();
  diagnostics_.friction_contacts =
      static_cast<int>(newton_.potential().friction().contacts().size());
  diagnostics_.contact_forces =
      pair_forces(*model_, newton_.potential(), x, *near_, diagnostics_.min_distance);
}

}  // namespace grip::solver
