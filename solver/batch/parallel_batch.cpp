#include "solver/batch/parallel_batch.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "solver/batch/model_batch.hpp"
#include "solver/batch/tbb_launcher.hpp"
#include "solver/kernels/contact_barrier.hpp"
#include "solver/kernels/friction_potential.hpp"
#include "solver/newton/step_targets.hpp"
#include "solver/parallel/step_contacts.hpp"
#include "solver/parallel/step_start_stages.hpp"
#include "solver/potential/contact_forces.hpp"

namespace grip::solver {
namespace {

// The default gravity's magnitude: the residual's scale, as NewtonSolver::begin_step has it.
constexpr double kStandardGravity = 9.81;  // m/s^2
// An environment without FEM bodies and at most this many DOFs (a rigid object and a hand's
// driven links: 17 bodies, 204 DOFs) is solved by dense Cholesky, the others by CG.
constexpr int kDenseDofs = 600;

using Mask = std::vector<unsigned char>;

bool any(const Mask& mask) {
  return std::any_of(mask.begin(), mask.end(), [](unsigned char m) { return m != 0; });
}

std::vector<const Model*> raw_models(const std::vector<std::shared_ptr<const Model>>& models) {
  std::vector<const Model*> raw;
  for (const auto& m : models) raw.push_back(m.get());
  return raw;
}

// CG's tolerance for an environment: what the CPU engine accepts of a solve by CG on an earlier
// factorization (reuse_tolerance); where that engine factorizes every system (reuse_iterations
// 0), as good as a direct solve.
double cg_tolerance(const SimParameters& sim) {
  return sim.reuse_iterations > 0 ? sim.reuse_tolerance : parallel::kExactCgTolerance;
}

// The CPU engine's failure of an iteration, and its message.
std::pair<Failure, std::string> iteration_failure(int code) {
  switch (code) {
    case parallel::kNewtonNonFinite:
      return {Failure::kNonFinite, "non-finite gradient or Newton step in Newton iteration"};
    case parallel::kNewtonLinearSolve:
      return {Failure::kLinearSolve, "Newton system not solved: CG did not converge"};
    case parallel::kNewtonNoMotion:
      return {Failure::kCcdNoMotion, "continuous collision detection allows no motion"};
    case parallel::kNewtonInversion:
      return {Failure::kInversion, "no step keeps every tetrahedron positively oriented"};
    default:
      break;
  }
  return {Failure::kLineSearch, "line search cannot decrease the incremental potential"};
}

}  // namespace

// The batch's flat buffers, built once from its models, and what its Newton iterations read.
struct ParallelBatch::Buffers {
  Buffers(std::vector<std::shared_ptr<const Model>> all, int thread_count)
      : models(std::move(all)),
        raw(raw_models(models)),
        fem(parallel::fem_batch(raw)),
        affine(parallel::affine_batch(raw)),
        collision(parallel::collision_batch(raw)),
        surface(parallel::surface_batch(raw)),
        newton(fem, affine, collision, surface),
        threads(thread_count) {
    newton.prescribed = parallel::prescribed_dofs(raw);
    newton.fixed = newton.prescribed;
    newton.prescribed_target.assign(newton.prescribed.size(), 0.0);
    newton.kappa.assign(raw.size(), 0.0);
    newton.held.assign(raw.size(), 0);
    for (std::size_t e = 0; e < raw.size(); ++e) add_parameters(*raw[e], static_cast<int>(e));
  }

  void add_parameters(const Model& model, int e) {
    const SimParameters& sim = model.sim();
    if (e > 0 && sim.ccd_rescaling != newton.ccd_rescaling) {
      throw std::invalid_argument("ParallelBatch: models with different ccd_rescaling");
    }
    newton.ccd_rescaling = sim.ccd_rescaling;
    newton.d_hat.push_back(sim.d_hat);
    newton.newton_tol.push_back(sim.newton_tol);
    newton.velocity_tol.push_back(sim.newton_velocity_tol);
    newton.projected_iterations.push_back(sim.projected_iterations);
    newton.cg_tolerance.push_back(cg_tolerance(sim));
    double weight = 0.0;
    for (const BodyModel& body : model.bodies()) {
      weight += body.kind->mass(body.local) * kStandardGravity;
    }
    newton.standard_weight.push_back(weight);
    const bool rigid = fem.tet_begin()[e + 1] == fem.tet_begin()[e];
    newton.dense.push_back(rigid && model.dof_count() <= kDenseDofs ? 1 : 0);
  }

  std::vector<std::shared_ptr<const Model>> models;
  std::vector<const Model*> raw;
  parallel::FemBatch fem;
  parallel::AffineBatch affine;
  parallel::CollisionBatch collision;
  parallel::SurfaceBatch surface;
  parallel::NewtonBatch newton;
  int threads;
  int rounds = 0;  // of the last step
};

namespace {

// Where one environment's step stands on the host: the whole step's end, the current part's
// depth, friction lag and targets. The part's start is the caller's state, which the batch
// writes only when the part ends (or the environment fails).
struct Plan {
  double end_time = 0.0;
  int halvings = 0;
  int lag = 0;
  StepTargets targets;
};

template <class Launcher>
class Stepper {
 public:
  Stepper(Launcher& launch, ParallelBatch::Buffers& b, std::vector<State>& states,
          const StepPolicy& policy)
      : launch_(launch), b_(b), nb_(b.newton), states_(states), policy_(policy) {}

  std::vector<ParallelStepResult> run(const Mask& stepping);

 private:
  int environments() const { return static_cast<int>(b_.raw.size()); }
  const Model& model(int e) const { return *b_.raw[e]; }
  int dof_begin(int e) const { return b_.collision.dof_begin()[e]; }

  void allocate();
  void load(int e);
  void begin_parts(const Mask& which);
  void lag(const Mask& which);
  void take_outcomes(Mask& begin, Mask& relag);
  void retry_or_fail(int e, Failure code, const std::string& why, Mask& begin);
  void fail(int e, Failure code, const std::string& why);
  void finish_converged_part(int e, Mask& begin);
  void finish_part(int e);
  void finish_step(int e);
  void record_contacts(int e);
  void start_solve(int e);
  std::vector<double> eps() const;
  std::vector<double> positions() const;
  void contact_diagnostics(int e, const Vertices& x, StepDiagnostics& d) const;

  Launcher& launch_;
  ParallelBatch::Buffers& b_;
  parallel::NewtonBatch& nb_;
  std::vector<State>& states_;
  const StepPolicy& policy_;
  parallel::NewtonIterate it_;
  std::vector<double> v_, gravity_;
  std::vector<Plan> plans_;
  std::vector<ParallelStepResult> results_;
};

template <class Launcher>
std::vector<ParallelStepResult> Stepper<Launcher>::run(const Mask& stepping) {
  allocate();
  for (int e = 0; e < environments(); ++e) {
    const State& s = states_[e];
    plans_[e].end_time = s.time + model(e).sim().dt;
    results_[e].stepped = stepping[e] != 0;
    results_[e].diagnostics.kappa = s.kappa;
    if (stepping[e] == 0) load(e);  // every environment's buffers hold its state
  }
  begin_parts(stepping);
  b_.rounds = 0;
  const auto iterating = [&] { return any(it_.active); };
  while (iterating()) {
    Mask begin(environments()), relag(environments());
    for (int e = 0; e < environments(); ++e) {
      const int limit = model(e).sim().max_newton_iters;
      if (it_.active[e] == 0 || it_.iteration[e] < limit) continue;
      retry_or_fail(e, Failure::kNewtonLimit,
                    "Newton did not converge in " + std::to_string(limit) + " iterations", begin);
    }
    if (any(begin)) begin_parts(begin);
    if (!iterating()) break;
    parallel::newton_iteration(launch_, nb_, it_);
    ++b_.rounds;
    begin.assign(environments(), 0);
    take_outcomes(begin, relag);
    if (any(relag)) lag(relag);
    if (any(begin)) begin_parts(begin);
  }
  return std::move(results_);
}

template <class Launcher>
void Stepper<Launcher>::allocate() {
  const int E = environments();
  const std::size_t dofs = nb_.prescribed.size();
  const std::size_t vertices = 3 * std::size_t(b_.collision.vertex_count());
  parallel::StepConstants& k = it_.step;
  k.h.assign(E, 0.0);
  k.progress.assign(E, 1.0);
  k.q_start.assign(dofs, 0.0);
  k.drive_target.assign(dofs, 0.0);
  k.scripted_start.assign(vertices, 0.0);
  k.scripted_target.assign(vertices, 0.0);
  it_.q.assign(dofs, 0.0);
  v_.assign(dofs, 0.0);
  gravity_.assign(3 * std::size_t(E), 0.0);
  it_.active.assign(E, 0);
  it_.iteration.assign(E, 0);
  it_.first_residual.assign(E, -1.0);
  it_.convergence_expected.assign(E, 0);
  plans_.assign(E, Plan{});
  results_.assign(E, ParallelStepResult{});
}

// The current part's start (states_[e]) and targets into the buffers.
template <class Launcher>
void Stepper<Launcher>::load(int e) {
  const Model& m = model(e);
  State& s = states_[e];
  Plan& plan = plans_[e];
  const double h = std::ldexp(m.sim().dt, -plan.halvings);
  plan.targets = step_targets(m, s, h);
  const int d0 = dof_begin(e);
  const int dofs = static_cast<int>(s.q.size());
  Eigen::VectorXd q_drive = s.q;
  for (std::size_t body = 0; body < m.bodies().size(); ++body) {
    const BodyModel& bm = m.bodies()[body];
    bm.kind->set_drive_target(bm.local, plan.targets.pose_target[body], q_drive);
  }
  parallel::StepConstants& k = it_.step;
  for (int d = 0; d < dofs; ++d) {
    it_.q[d0 + d] = k.q_start[d0 + d] = s.q[d];
    v_[d0 + d] = s.v[d];
    k.drive_target[d0 + d] = q_drive[d];
    nb_.prescribed_target[d0 + d] = plan.targets.prescribed_target[d];
    const bool held = !s.held.empty() && s.held[d] != 0;
    nb_.fixed[d0 + d] = nb_.prescribed[d0 + d] != 0 || held ? 1 : 0;
  }
  const std::size_t v0 = 3 * std::size_t(b_.collision.vertex_begin()[e]);
  const Vertices& start = plan.targets.kinematic_start;
  const Vertices& target = plan.targets.kinematic_target;
  std::copy(start.data(), start.data() + start.size(), k.scripted_start.begin() + v0);
  std::copy(target.data(), target.data() + target.size(), k.scripted_target.begin() + v0);
  for (int i = 0; i < 3; ++i) gravity_[3 * e + i] = s.gravity[i];
  nb_.kappa[e] = s.kappa;
  k.h[e] = h;
  k.progress[e] = 0.0;
}

template <class Launcher>
void Stepper<Launcher>::start_solve(int e) {
  it_.iteration[e] = 0;
  it_.first_residual[e] = -1.0;
  it_.convergence_expected[e] = 0;
  it_.active[e] = 1;
}

// A part begins for the environments `which` marks: their buffers, the step's constants and
// the contacts at their start. The others' constants come out as they were (the same inputs);
// their contacts are kept.
template <class Launcher>
void Stepper<Launcher>::begin_parts(const Mask& which) {
  for (int e = 0; e < environments(); ++e) {
    if (which[e] == 0) continue;
    load(e);
    plans_[e].lag = 0;
  }
  parallel::fill_step_start_constants(it_.step, b_.fem, b_.affine, b_.collision, v_, gravity_);
  parallel::StepContacts c = parallel::contacts_at(launch_, nb_, it_.step.start_positions, eps(),
                                                   policy_.friction_terms_at_zero_mu);
  const bool first = it_.pairs.environment_count() == 0;
  it_.pairs = first ? std::move(c.pairs) : parallel::chosen_pairs(it_.pairs, c.pairs, which);
  it_.friction =
      first ? std::move(c.friction) : parallel::chosen_friction(it_.friction, c.friction, which);
  for (int e = 0; e < environments(); ++e) {
    if (which[e] != 0) start_solve(e);
  }
}

// A further friction lag at the current positions; the barrier's pairs are kept.
template <class Launcher>
void Stepper<Launcher>::lag(const Mask& which) {
  const parallel::FrictionContacts fresh =
      parallel::friction_at(launch_, nb_, positions(), eps(), policy_.friction_terms_at_zero_mu);
  it_.friction = parallel::chosen_friction(it_.friction, fresh, which);
  for (int e = 0; e < environments(); ++e) {
    if (which[e] != 0) start_solve(e);
  }
}

template <class Launcher>
void Stepper<Launcher>::take_outcomes(Mask& begin, Mask& relag) {
  for (int e = 0; e < environments(); ++e) {
    const int outcome = it_.outcome[e];
    if (outcome == parallel::kNewtonIdle) continue;
    ParallelStepResult& r = results_[e];
    const double h = it_.step.h[e];
    ++r.diagnostics.newton_iterations;
    r.diagnostics.residual = it_.residual[e] / (h * h);
    r.cg_iterations += it_.cg_iterations[e];
    if (outcome == parallel::kNewtonContinue) continue;
    it_.active[e] = 0;
    if (outcome == parallel::kNewtonFailed) {
      const auto [code, why] = iteration_failure(it_.failure[e]);
      retry_or_fail(e, code, why, begin);
    } else if (++plans_[e].lag < std::max(1, model(e).sim().friction_lag_iterations)) {
      relag[e] = 1;
    } else {
      finish_converged_part(e, begin);
    }
  }
}

// Retries the failed part as two halves from its start (still the caller's state), or fails
// the environment when the parts are already as short as max_step_halvings allows.
template <class Launcher>
void Stepper<Launcher>::retry_or_fail(int e, Failure code, const std::string& why, Mask& begin) {
  it_.active[e] = 0;
  Plan& plan = plans_[e];
  if (plan.halvings >= model(e).sim().max_step_halvings) {
    const std::string depth =
        plan.halvings > 0 ? " (after " + std::to_string(plan.halvings) + " halvings of dt)" : "";
    fail(e, code, why + depth);
    return;
  }
  ++plan.halvings;
  ++results_[e].diagnostics.retries;
  begin[e] = 1;
}

// The environment keeps the positions its failed iteration reached, as the CPU engine's does.
template <class Launcher>
void Stepper<Launcher>::fail(int e, Failure code, const std::string& why) {
  State& s = states_[e];
  std::copy(it_.q.begin() + dof_begin(e), it_.q.begin() + dof_begin(e) + s.q.size(), s.q.data());
  results_[e].failure = code;
  results_[e].message = "t = " + std::to_string(s.time) + " s: " + why;
  record_contacts(e);
}

template <class Launcher>
void Stepper<Launcher>::finish_converged_part(int e, Mask& begin) {
  const bool last_part = states_[e].time + 1.5 * it_.step.h[e] >= plans_[e].end_time;
  if (last_part) {
    finish_step(e);
    return;
  }
  finish_part(e);
  begin[e] = 1;
}

template <class Launcher>
void Stepper<Launcher>::finish_part(int e) {
  const Model& m = model(e);
  State& s = states_[e];
  const Plan& plan = plans_[e];
  const double h = it_.step.h[e];
  std::copy(it_.q.begin() + dof_begin(e), it_.q.begin() + dof_begin(e) + s.q.size(), s.q.data());
  s.v = (s.q - plan.targets.q_start) / h;
  for (std::size_t body = 0; body < m.bodies().size(); ++body) {
    if (!m.bodies()[body].scripted()) continue;
    s.kinematic_velocity[body] =
        (plan.targets.pose_target[body].position - s.poses[body].position) / h;
    s.poses[body] = plan.targets.pose_target[body];
  }
  s.time += h;
}

template <class Launcher>
void Stepper<Launcher>::finish_step(int e) {
  const Model& m = model(e);
  State& s = states_[e];
  finish_part(e);
  // Parts of a retried step add up to dt; the clock says so without their round-off.
  if (plans_[e].halvings > 0) s.time = plans_[e].end_time;
  StepDiagnostics& d = results_[e].diagnostics;
  const Vertices x = collision_positions(m, s.q, plans_[e].targets, 1.0);
  contact_diagnostics(e, x, d);
  d.min_volume_ratio = m.min_volume_ratio(s.q);
  d.friction_contacts = it_.friction.contact_begin()[e + 1] - it_.friction.contact_begin()[e];
  record_contacts(e);
  if (m.sim().adaptive_kappa && d.min_distance < 0.1 * m.sim().d_hat) s.kappa *= 2.0;
}

// The contacts the environment's potential ends the step with, in its own vertex numbering.
// A FrictionContact's edge_edge only picks the vertex whose body is side B in sums per pair of
// bodies; the batch does not keep the kind, and vertex 2 is side B of either kind
// (contact_diagnostics), so every contact is marked edge-edge.
template <class Launcher>
void Stepper<Launcher>::record_contacts(int e) {
  ParallelStepResult& r = results_[e];
  const int v0 = b_.collision.vertex_begin()[e];
  const int vertices = b_.collision.vertex_begin()[e + 1] - v0;
  r.start_positions =
      Eigen::Map<const Vertices>(it_.step.start_positions.data() + 3 * v0, vertices, 3);
  r.h = it_.step.h[e];
  r.kappa = nb_.kappa[e];
  const parallel::FrictionContacts& friction = it_.friction;
  const int first = friction.vertex_begin()[e];
  r.friction.clear();
  for (int k = friction.contact_begin()[e]; k < friction.contact_begin()[e + 1]; ++k) {
    FrictionContact c;
    for (int i = 0; i < 4; ++i) c.vertex[i] = friction.vertex()[4 * std::size_t(k) + i] - first;
    c.edge_edge = true;
    c.mu_lambda = friction.mu_lambda()[k];
    c.tangent_operator =
        Eigen::Map<const Eigen::Matrix<double, 12, 2>>(&friction.tangent()[24 * std::size_t(k)]);
    r.friction.push_back(c);
  }
}

// At x (the step's end), as the CPU engine's pair_forces measures them: the closest of the
// barrier's pairs within d_hat, and the contact forces per pair of bodies, each pair's barrier
// force where it pushes and each lagged friction contact's force (PairForceSum).
template <class Launcher>
void Stepper<Launcher>::contact_diagnostics(int e, const Vertices& x, StepDiagnostics& d) const {
  PairForceSum forces(model(e).collision().vertex_body);
  const parallel::ContactPairs& pairs = it_.pairs;
  const int first_vertex = pairs.vertex_begin()[e];
  const double d_hat = pairs.d_hat()[e], kappa = pairs.kappa()[e];
  for (int k = pairs.pair_begin()[e]; k < pairs.pair_begin()[e + 1]; ++k) {
    int local[4];
    Eigen::Vector3d corners[4];
    for (int i = 0; i < 4; ++i) {
      local[i] = pairs.vertex()[4 * std::size_t(k) + i] - first_vertex;
      corners[i] = x.row(local[i]).transpose();
    }
    const bool edge_edge = pairs.edge_edge()[k] != 0;
    const double distance = std::sqrt(kernels::contact_squared_distance(edge_edge, corners));
    if (distance < d_hat) d.min_distance = std::min(d.min_distance, distance);
    const double eps = pairs.mollifier_eps()[k];
    const double normal = kernels::contact_normal_force(edge_edge, eps, corners, d_hat, kappa);
    if (normal > 0.0) {
      forces.add(local, edge_edge ? 2 : 1,
                 -kernels::contact_barrier(edge_edge, eps, corners, d_hat, kappa, false).gradient,
                 normal);
    }
  }
  const parallel::FrictionContacts& friction = it_.friction;
  const std::vector<double>& start = it_.step.start_positions;
  for (int k = friction.contact_begin()[e]; k < friction.contact_begin()[e + 1]; ++k) {
    int local[4];
    Eigen::Matrix<double, 12, 1> dx;
    for (int i = 0; i < 4; ++i) {
      const int v = friction.vertex()[4 * std::size_t(k) + i];
      local[i] = v - first_vertex;
      for (int c = 0; c < 3; ++c) dx[3 * i + c] = x(local[i], c) - start[3 * std::size_t(v) + c];
    }
    const Eigen::Map<const Eigen::Matrix<double, 12, 2>> tangent(
        &friction.tangent()[24 * std::size_t(k)]);
    // Side B is vertex 2's body: a triangle's or the second edge's.
    forces.add(local, 2,
               -kernels::friction_potential_gradient<4>(dx, tangent, friction.mu_lambda()[k],
                                                        friction.eps()[e]),
               0.0);
  }
  d.contact_forces = forces.pairs();
}

template <class Launcher>
std::vector<double> Stepper<Launcher>::eps() const {
  std::vector<double> eps(environments());
  for (int e = 0; e < environments(); ++e) eps[e] = model(e).sim().eps_v * it_.step.h[e];
  return eps;
}

// The collision vertices where the current iterate has them.
template <class Launcher>
std::vector<double> Stepper<Launcher>::positions() const {
  std::vector<double> x(3 * std::size_t(b_.collision.vertex_count()));
  launch_(
      b_.collision.vertex_count(),
      parallel::PositionStage{b_.collision.vertices(), it_.q.data(), it_.step.scripted_start.data(),
                              it_.step.scripted_target.data(), it_.step.progress.data(), x.data()});
  return x;
}

}  // namespace

ParallelBatch::ParallelBatch(std::vector<std::shared_ptr<const Model>> models, int threads)
    : buffers_(std::make_unique<Buffers>(std::move(models), threads)) {}

ParallelBatch::~ParallelBatch() = default;

int ParallelBatch::size() const { return static_cast<int>(buffers_->raw.size()); }

int ParallelBatch::rounds() const { return buffers_->rounds; }

std::vector<ParallelStepResult> ParallelBatch::step(std::vector<State>& states,
                                                    const Mask& stepping,
                                                    const StepPolicy& policy) {
  if (!policy.freeze_converged) {
    throw std::invalid_argument("ParallelBatch: steps held open are not supported");
  }
  if (static_cast<int>(states.size()) != size() || static_cast<int>(stepping.size()) != size()) {
    throw std::invalid_argument("ParallelBatch::step: one state and flag per environment");
  }
  if (buffers_->threads == 1) {
    parallel::SerialLauncher launch;
    return Stepper<parallel::SerialLauncher>(launch, *buffers_, states, policy).run(stepping);
  }
  parallel::TbbLauncher launch(buffers_->threads);
  return Stepper<parallel::TbbLauncher>(launch, *buffers_, states, policy).run(stepping);
}

}  // namespace grip::solver
