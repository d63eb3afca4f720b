#include "solver/environment.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>

#include "solver/contact/candidates.hpp"
#include "solver/contact/contact_frame.hpp"
#include "solver/kernels/accd.hpp"
#include "solver/kernels/affine_body.hpp"
#include "solver/kernels/neo_hookean.hpp"
#include "solver/linear/blas_threads.hpp"

namespace grip::solver {

// What the step is heading for: the start state, and where kinematic bodies and pinned
// vertices must be at its end. Prescribed motion is applied progressively (progress 0 -> 1) so
// that CCD can stop it short of a contact and Newton can make room before it goes on.
struct Environment::StepTargets {
  Eigen::VectorXd q_start;
  Eigen::VectorXd prescribed_target;  // valid at prescribed DOFs
  Vertices kinematic_start;           // valid at kinematic collision vertices
  Vertices kinematic_target;
  std::vector<Pose> pose_target;
};

// Where a step under way stands: its targets, how much of the prescribed motion is done, which
// friction lag and Newton iteration it is in, and the residual scale of the current solve.
struct Environment::StepState {
  StepTargets targets;
  double progress = 0.0;
  int lag = 0;
  int iteration = 0;  // within the current lag's solve
  bool held = false;  // converged, held open by hold_converged
  double first_residual = 0.0;
  double weight = 0.0;  // N, of the dynamic bodies under the current gravity
  Eigen::VectorXd gradient;
  Eigen::VectorXd kinematic_force;
  std::vector<Eigen::Triplet<double>> triplets;
  std::vector<Eigen::Triplet<double>> free_triplets;
};

namespace {

Pose keyframe_pose(const std::vector<Keyframe>& keys, double time) {
  if (time <= keys.front().time) return keys.front().pose;
  if (time >= keys.back().time) return keys.back().pose;
  std::size_t i = 1;
  while (keys[i].time < time) ++i;
  const Keyframe& a = keys[i - 1];
  const Keyframe& b = keys[i];
  const double s = (time - a.time) / (b.time - a.time);
  Pose pose;
  pose.position = (1.0 - s) * a.pose.position + s * b.pose.position;
  pose.rotation = a.pose.rotation.slerp(s, b.pose.rotation);
  return pose;
}

Pose advance(const Script& script, const Pose& current, double next_time, double h) {
  if (!script.keyframes.empty()) return keyframe_pose(script.keyframes, next_time);
  Pose pose;
  pose.position = current.position + h * script.velocity;
  const double angle = script.angular_velocity.norm() * h;
  pose.rotation = current.rotation;
  if (angle > 0.0) {
    pose.rotation =
        Eigen::Quaterniond(Eigen::AngleAxisd(angle, script.angular_velocity.normalized())) *
        current.rotation;
  }
  pose.rotation.normalize();
  return pose;
}

Eigen::Vector3d apply(const Pose& pose, const Eigen::Vector3d& point) {
  return pose.rotation * point + pose.position;
}

Eigen::Matrix3d nearest_rotation(const Eigen::Matrix3d& m) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  d(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
  return svd.matrixU() * d * svd.matrixV().transpose();
}

double tet_volume_ratio(const Eigen::VectorXd& q, const BodyModel& body, const FemTet& tet) {
  Eigen::Matrix<double, 12, 1> x;
  for (int i = 0; i < 4; ++i)
    x.segment<3>(3 * i) = q.segment<3>(body.dof_offset + 3 * tet.vertices[i]);
  return kernels::deformation_gradient(x, tet.rest_shape_inverse).determinant();
}

double min_volume_ratio_of(const Model& model, const Eigen::VectorXd& q) {
  double ratio = 1.0;
  for (const BodyModel& body : model.bodies()) {
    for (const FemTet& tet : body.tets) ratio = std::min(ratio, tet_volume_ratio(q, body, tet));
  }
  return ratio;
}

// The largest displacement of any vertex under the DOF change dq (m).
double max_vertex_displacement(const Model& model, const Eigen::VectorXd& dq) {
  double largest = 0.0;
  for (const BodyModel& body : model.bodies()) {
    if (body.type == BodyType::kFem) {
      for (Eigen::Index v = 0; v < body.rest.rows(); ++v) {
        largest = std::max(largest, dq.segment<3>(body.dof_offset + 3 * v).norm());
      }
    } else if (body.type == BodyType::kAffine) {
      const Vector12d db = dq.segment<12>(body.dof_offset);
      for (Eigen::Index v = 0; v < body.rest.rows(); ++v) {
        const Eigen::Vector3d rest = body.rest.row(v);
        largest = std::max(largest, (kernels::affine_body_jacobian(rest) * db).norm());
      }
    }
  }
  return largest;
}

kernels::AccdResult time_of_impact(const ContactPair& pair, const Vertices& start,
                                   const Vertices& end, double rescaling) {
  kernels::AccdOptions options;
  options.rescaling = rescaling;
  const auto& v = pair.vertex;
  auto s = [&](int i) -> Eigen::Vector3d { return start.row(v[i]); };
  auto e = [&](int i) -> Eigen::Vector3d { return end.row(v[i]); };
  return pair.edge_edge
             ? kernels::edge_edge_accd(s(0), s(1), s(2), s(3), e(0), e(1), e(2), e(3), options)
             : kernels::point_triangle_accd(s(0), s(1), s(2), s(3), e(0), e(1), e(2), e(3),
                                            options);
}

}  // namespace

Environment::Environment(std::shared_ptr<const Model> model)
    : model_(std::move(model)),
      gravity_(model_->sim().gravity),
      kappa_(model_->sim().kappa),
      potential_(*model_),
      cholesky_(model_->ordering()) {
  // Environments run side by side on threads of their own (solver/batch); a BLAS threading
  // inside each factorization would oversubscribe the cores.
  static std::once_flag blas_configured;
  std::call_once(blas_configured, use_single_threaded_blas);
  const SceneDescription& scene = model_->scene();
  q_.setZero(model_->dof_count());
  v_.setZero(model_->dof_count());
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const BodyDescription& d = scene.bodies[b];
    const BodyModel& body = model_->bodies()[b];
    const Eigen::Matrix3d r = d.pose.rotation.normalized().toRotationMatrix();
    poses_.push_back(d.pose);
    scripts_.push_back(d.script);
    kinematic_velocity_.push_back(d.script.keyframes.empty() ? d.script.velocity
                                                             : Eigen::Vector3d::Zero());
    if (body.type == BodyType::kFem) {
      Eigen::Vector3d com = Eigen::Vector3d::Zero();
      for (Eigen::Index v = 0; v < body.rest.rows(); ++v) {
        com += body.vertex_mass[v] * body.rest.row(v).transpose();
      }
      com /= body.vertex_mass.sum();
      for (Eigen::Index v = 0; v < body.rest.rows(); ++v) {
        const Eigen::Vector3d x = body.rest.row(v);
        q_.segment<3>(body.dof_offset + 3 * v) = x;
        v_.segment<3>(body.dof_offset + 3 * v) = d.velocity + d.angular_velocity.cross(x - com);
      }
    } else if (body.type == BodyType::kAffine) {
      const Eigen::Vector3d com = d.pose.position + r * body.center_of_mass_offset;
      q_.segment<12>(body.dof_offset) = kernels::affine_body_dofs(r, com);
      // dA/dt = [omega]x A; q is linear in (A, p), so the same map gives the DOF velocity.
      Eigen::Matrix3d omega_cross;
      omega_cross << 0, -d.angular_velocity.z(), d.angular_velocity.y(), d.angular_velocity.z(), 0,
          -d.angular_velocity.x(), -d.angular_velocity.y(), d.angular_velocity.x(), 0;
      v_.segment<12>(body.dof_offset) = kernels::affine_body_dofs(omega_cross * r, d.velocity);
    }
  }
}

Environment::~Environment() = default;
Environment::Environment(Environment&&) noexcept = default;

void Environment::place(int index, const Eigen::Isometry3d& motion) {
  if (time_ != 0.0 || step_) throw std::logic_error("Environment::place after the first step");
  const BodyModel& body = model_->bodies().at(static_cast<std::size_t>(index));
  const Eigen::Matrix3d r = motion.linear();
  const Eigen::Vector3d t = motion.translation();
  switch (body.type) {
    case BodyType::kFem:
      for (Eigen::Index v = 0; v < body.rest.rows(); ++v) {
        const int o = body.dof_offset + 3 * static_cast<int>(v);
        q_.segment<3>(o) = r * q_.segment<3>(o) + t;
        v_.segment<3>(o) = r * v_.segment<3>(o);
      }
      break;
    case BodyType::kAffine: {
      const Vector12d q = q_.segment<12>(body.dof_offset), v = v_.segment<12>(body.dof_offset);
      q_.segment<12>(body.dof_offset) =
          kernels::affine_body_dofs(r * kernels::affine_body_matrix(q), r * q.segment<3>(0) + t);
      v_.segment<12>(body.dof_offset) =
          kernels::affine_body_dofs(r * kernels::affine_body_matrix(v), r * v.segment<3>(0));
      break;
    }
    case BodyType::kKinematic:
      poses_[index].position = r * poses_[index].position + t;
      poses_[index].rotation = Eigen::Quaterniond(r) * poses_[index].rotation;
      poses_[index].rotation.normalize();
      kinematic_velocity_[index] = r * kinematic_velocity_[index];
      break;
  }
}

void Environment::set_script(int body, const Script& script) {
  scripts_.at(static_cast<std::size_t>(body)) = script;
}

void Environment::use_linear_solver(std::shared_ptr<LinearSystemSolver> solver, int min_dofs) {
  linear_solver_ = std::move(solver);
  linear_solver_min_dofs_ = min_dofs;
}

Environment::Progress Environment::fail(const std::string& reason) {
  failure_ = "t = " + std::to_string(time_) + " s: " + reason;
  step_.reset();
  return Progress::kFailed;
}

Vertices Environment::positions_at(const Eigen::VectorXd& q, const StepTargets& targets,
                                   double progress) const {
  const CollisionMesh& mesh = model_->collision();
  Vertices x(mesh.size(), 3);
  for (int i = 0; i < mesh.size(); ++i) {
    const BodyModel& body = model_->bodies()[mesh.vertex_body[i]];
    const int local = mesh.vertex_local[i];
    switch (body.type) {
      case BodyType::kFem:
        x.row(i) = q.segment<3>(body.dof_offset + 3 * local);
        break;
      case BodyType::kAffine:
        x.row(i) = kernels::affine_body_position(q.segment<12>(body.dof_offset),
                                                 body.rest.row(local).transpose());
        break;
      case BodyType::kKinematic:
        x.row(i) = (1.0 - progress) * targets.kinematic_start.row(i) +
                   progress * targets.kinematic_target.row(i);
        break;
    }
  }
  return x;
}

Vertices Environment::collision_positions() const {
  StepTargets now;
  const CollisionMesh& mesh = model_->collision();
  now.kinematic_start.resize(mesh.size(), 3);
  for (int i = 0; i < mesh.size(); ++i) {
    const BodyModel& body = model_->bodies()[mesh.vertex_body[i]];
    if (body.type == BodyType::kKinematic) {
      now.kinematic_start.row(i) =
          apply(poses_[mesh.vertex_body[i]], body.rest.row(mesh.vertex_local[i]).transpose());
    }
  }
  now.kinematic_target = now.kinematic_start;
  return positions_at(q_, now, 0.0);
}

Vertices Environment::body_vertices(int index) const {
  const BodyModel& body = model_->bodies()[index];
  Vertices x(body.rest.rows(), 3);
  for (Eigen::Index v = 0; v < body.rest.rows(); ++v) {
    const Eigen::Vector3d rest = body.rest.row(v);
    switch (body.type) {
      case BodyType::kFem:
        x.row(v) = q_.segment<3>(body.dof_offset + 3 * v);
        break;
      case BodyType::kAffine:
        x.row(v) = kernels::affine_body_position(q_.segment<12>(body.dof_offset), rest);
        break;
      case BodyType::kKinematic:
        x.row(v) = apply(poses_[index], rest);
        break;
    }
  }
  return x;
}

namespace {

// The lumped-mass-weighted mean of an FEM body's per-vertex 3-vectors in `values` (positions
// or velocities).
Eigen::Vector3d mass_weighted_mean(const BodyModel& body, const Eigen::VectorXd& values) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (Eigen::Index v = 0; v < body.rest.rows(); ++v) {
    sum += body.vertex_mass[v] * values.segment<3>(body.dof_offset + 3 * v);
  }
  return sum / body.vertex_mass.sum();
}

}  // namespace

Eigen::Vector3d Environment::center_of_mass(int index) const {
  const BodyModel& body = model_->bodies()[index];
  if (body.type == BodyType::kAffine) return q_.segment<3>(body.dof_offset);
  if (body.type == BodyType::kKinematic) return poses_[index].position;
  return mass_weighted_mean(body, q_);
}

Eigen::Vector3d Environment::center_of_mass_velocity(int index) const {
  const BodyModel& body = model_->bodies()[index];
  if (body.type == BodyType::kAffine) return v_.segment<3>(body.dof_offset);
  if (body.type == BodyType::kKinematic) return kinematic_velocity_[index];
  return mass_weighted_mean(body, v_);
}

Eigen::Matrix3d Environment::rotation(int index) const {
  const BodyModel& body = model_->bodies()[index];
  if (body.type == BodyType::kAffine) {
    return nearest_rotation(kernels::affine_body_matrix(q_.segment<12>(body.dof_offset)));
  }
  if (body.type == BodyType::kKinematic) return poses_[index].rotation.toRotationMatrix();
  // FEM: the rotation of the best rigid fit of the vertices to the rest shape.
  const double mass = body.vertex_mass.sum();
  Eigen::Vector3d rest_com = Eigen::Vector3d::Zero();
  for (Eigen::Index v = 0; v < body.rest.rows(); ++v) {
    rest_com += body.vertex_mass[v] * body.rest.row(v).transpose();
  }
  rest_com /= mass;
  const Eigen::Vector3d com = center_of_mass(index);
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (Eigen::Index v = 0; v < body.rest.rows(); ++v) {
    covariance += body.vertex_mass[v] * (q_.segment<3>(body.dof_offset + 3 * v) - com) *
                  (body.rest.row(v).transpose() - rest_com).transpose();
  }
  return nearest_rotation(covariance);
}

double Environment::min_volume_ratio() const { return min_volume_ratio_of(*model_, q_); }

std::vector<FrictionContact> Environment::lag_friction(const Vertices& positions) const {
  std::vector<FrictionContact> contacts;
  const double d_hat = model_->sim().d_hat;
  for (const ContactPair& pair : find_contact_pairs(*model_, positions, positions, d_hat)) {
    if (pair.friction <= 0.0 && !friction_terms_at_zero_mu_) continue;  // none where mu = 0
    const ContactForce force = potential_.contact_force(pair, positions);
    if (force.magnitude <= 0.0) continue;
    Eigen::Vector3d x[4];
    for (int i = 0; i < 4; ++i) x[i] = positions.row(pair.vertex[i]);
    const ContactFrame frame = pair.edge_edge ? edge_edge_frame(x) : point_triangle_frame(x);
    contacts.push_back(
        {pair.vertex, pair.edge_edge, pair.friction * force.magnitude, frame.tangent_operator()});
  }
  return contacts;
}

Environment::NewtonOutcome Environment::newton_iteration(StepState& state) {
  const SimParameters& sim = model_->sim();
  if (state.iteration == sim.max_newton_iters && !state.held) {
    fail("Newton did not converge in " + std::to_string(sim.max_newton_iters) + " iterations");
    return NewtonOutcome::kFailed;
  }
  const int iteration = state.iteration++;
  auto give_up = [this](const std::string& reason) {
    fail(reason);
    return NewtonOutcome::kFailed;
  };
  const int n = model_->dof_count();
  const std::vector<char>& prescribed = model_->prescribed();
  const double h = sim.dt;
  StepTargets& targets = state.targets;
  double& progress = state.progress;

  ++diagnostics_.newton_iterations;
  ++statistics_.newton_iterations;
  statistics_.max_step_iterations =
      std::max(statistics_.max_step_iterations, diagnostics_.newton_iterations);
  const Vertices x = positions_at(q_, targets, progress);
  const std::vector<ContactPair> near = find_contact_pairs(*model_, x, x, sim.d_hat);
  // Prescribed motion still to come: pinned DOFs (`lift`) and kinematic vertices. Pinned
  // DOFs are eliminated, H_ff p_f = -(g_f + H_fp lift_p + H_fk dk), p_p = lift_p.
  const bool moving = progress < 1.0;
  const Vertices kinematic_motion = positions_at(q_, targets, 1.0) - x;
  Eigen::VectorXd& gradient = state.gradient;
  potential_.derivatives(q_, x, near, gradient, state.triplets,
                         moving ? &kinematic_motion : nullptr, &state.kinematic_force);
  if (!gradient.allFinite()) return give_up("non-finite gradient in Newton iteration");
  Eigen::VectorXd lift = Eigen::VectorXd::Zero(n);
  if (moving) {
    for (int i = 0; i < n; ++i) {
      if (prescribed[i]) lift[i] = targets.prescribed_target[i] - q_[i];
    }
  }
  Eigen::VectorXd rhs = -gradient - state.kinematic_force;
  std::vector<Eigen::Triplet<double>>& free_triplets = state.free_triplets;
  free_triplets.clear();
  for (const auto& e : state.triplets) {
    const int r = static_cast<int>(e.row()), c = static_cast<int>(e.col());
    if (moving) {
      rhs[r] -= e.value() * lift[c];
      if (r != c) rhs[c] -= e.value() * lift[r];
    }
    if (!prescribed[r] && !prescribed[c]) free_triplets.push_back(e);
  }
  double residual = 0.0;
  for (int i = 0; i < n; ++i) {
    if (prescribed[i]) {
      free_triplets.emplace_back(i, i, 1.0);
      rhs[i] = lift[i];
    } else {
      residual = std::max(residual, std::abs(gradient[i]));
    }
  }
  // The residual's scale: this solve's first residual, and never less than the weight of
  // the dynamic bodies, so a body resting in equilibrium is not asked for round-off.
  if (iteration == 0) state.first_residual = std::max(residual, state.weight * h * h);
  diagnostics_.residual = residual / (h * h);
  Eigen::VectorXd p;
  if (linear_solver_ && n >= linear_solver_min_dofs_) {
    LinearSystemSolver& solver = *linear_solver_;
    if (!solver.factorize(assembly_.assemble(n, free_triplets)) || !solver.solve(rhs, p)) {
      return give_up("Newton system not solved: " + solver.failure());
    }
  } else {
    if (!cholesky_.factorize(assembly_.assemble(n, free_triplets))) {
      return give_up("Newton matrix is not positive definite");
    }
    p = cholesky_.solve(rhs);
  }
  if (!p.allFinite()) return give_up("non-finite Newton step");

  // Converged: the residual fell by newton_tol against its scale, or the step would change
  // no vertex's velocity by more than newton_velocity_tol. A test on the step's length alone
  // is not enough: near d_hat the barrier (and sticking friction) is so stiff that a
  // micrometre off leaves the normal force, and friction's lagged lambda, wrong.
  if (!moving && !state.held && (residual <= sim.newton_tol * state.first_residual ||
                  max_vertex_displacement(*model_, p) <= sim.newton_velocity_tol * h)) {
    return NewtonOutcome::kConverged;
  }

  // Line search: CCD's safe fraction of the step, then positive volumes, then (once the
  // prescribed motion is done) Armijo on the incremental potential.
  const Vertices x_end = positions_at(q_ + p, targets, 1.0);
  const std::vector<ContactPair> swept = find_contact_pairs(*model_, x, x_end, sim.d_hat);
  double alpha = 1.0;
  for (const ContactPair& pair : swept) {
    const kernels::AccdResult impact = time_of_impact(pair, x, x_end, sim.ccd_rescaling);
    if (impact.impact) alpha = std::min(alpha, impact.toi);
  }
  if (!(alpha > 0.0)) return give_up("continuous collision detection allows no motion");
  while (min_volume_ratio_of(*model_, q_ + alpha * p) <= 0.0) {
    alpha *= 0.5;
    ++diagnostics_.line_search_steps;
    if (alpha < 1e-12) return give_up("no step keeps every tetrahedron positively oriented");
  }
  if (!moving) {
    const double energy = potential_.energy(q_, x, swept);
    const double slope = gradient.dot(p);
    for (;;) {
      const Eigen::VectorXd trial = q_ + alpha * p;
      // A held step's energy is one term of a monolithic solve's sum, whose decrease decides:
      // it is evaluated but not halved on its own.
      if (potential_.energy(trial, positions_at(trial, targets, 1.0), swept) <=
              energy + 1e-4 * alpha * slope ||
          state.held) {
        break;
      }
      alpha *= 0.5;
      ++diagnostics_.line_search_steps;
      if (alpha < 1e-12) return give_up("line search cannot decrease the incremental potential");
    }
  }
  q_ += alpha * p;
  progress = alpha >= 1.0 ? 1.0 : progress + alpha * (1.0 - progress);
  return NewtonOutcome::kContinue;
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
  const SimParameters& sim = model_->sim();
  const double h = sim.dt;
  const CollisionMesh& mesh = model_->collision();
  const int body_count = static_cast<int>(model_->bodies().size());
  diagnostics_ = StepDiagnostics{};
  diagnostics_.kappa = kappa_;

  step_ = std::make_unique<StepState>();
  StepTargets& targets = step_->targets;
  targets.q_start = q_;
  targets.pose_target.resize(body_count);
  for (int b = 0; b < body_count; ++b) {
    targets.pose_target[b] = model_->bodies()[b].type == BodyType::kKinematic
                                 ? advance(scripts_[b], poses_[b], time_ + h, h)
                                 : poses_[b];
  }
  targets.kinematic_start.setZero(mesh.size(), 3);
  targets.kinematic_target.setZero(mesh.size(), 3);
  for (int i = 0; i < mesh.size(); ++i) {
    const int b = mesh.vertex_body[i];
    if (model_->bodies()[b].type != BodyType::kKinematic) continue;
    const Eigen::Vector3d rest = model_->bodies()[b].rest.row(mesh.vertex_local[i]);
    targets.kinematic_start.row(i) = apply(poses_[b], rest);
    targets.kinematic_target.row(i) = apply(targets.pose_target[b], rest);
  }
  targets.prescribed_target = q_;
  for (const PinnedVertex& pin : model_->pins()) {
    const int o = model_->bodies()[pin.body].dof_offset + 3 * pin.vertex;
    targets.prescribed_target.segment<3>(o) =
        apply(targets.pose_target[pin.kinematic_body], pin.offset);
  }

  const Vertices start = positions_at(q_, targets, 0.0);
  if (time_ == 0.0) {
    for (const ContactPair& pair : find_contact_pairs(*model_, start, start, sim.d_hat)) {
      if (!(potential_.contact_force(pair, start).distance > 0.0)) {
        return fail("intersecting start: two surfaces touch or cross before the first step");
      }
    }
  }

  // The inertia target: x_tilde = x + h v + h^2 M^-1 f_gravity.
  Eigen::VectorXd q_tilde = q_ + h * v_;
  for (const BodyModel& body : model_->bodies()) {
    if (body.type == BodyType::kFem) {
      for (Eigen::Index v = 0; v < body.rest.rows(); ++v) {
        q_tilde.segment<3>(body.dof_offset + 3 * v) += h * h * gravity_;
      }
      step_->weight += body.vertex_mass.sum() * gravity_.norm();
    } else if (body.type == BodyType::kAffine) {
      const Vector12d force = body.material.density * body.volume *
                              kernels::affine_body_jacobian(Eigen::Vector3d::Zero()).transpose() *
                              gravity_;
      q_tilde.segment<12>(body.dof_offset) += h * h * body.mass_matrix_inverse * force;
      step_->weight += body.mass_matrix(0, 0) * gravity_.norm();
    }
  }

  potential_.begin_step(q_tilde, start, kappa_);
  potential_.set_friction(lag_friction(start));
  return Progress::kIterating;
}

Environment::Progress Environment::iterate() {
  if (failed()) return Progress::kFailed;
  if (!step_) throw std::logic_error("Environment::iterate without begin_step");
  StepState& state = *step_;
  switch (newton_iteration(state)) {
    case NewtonOutcome::kFailed:
      return Progress::kFailed;
    case NewtonOutcome::kContinue:
      return state.held ? Progress::kConverged : Progress::kIterating;
    case NewtonOutcome::kConverged:
      break;
  }
  // Each further friction lag re-linearizes friction at the current positions and solves again.
  if (++state.lag < std::max(1, model_->sim().friction_lag_iterations)) {
    potential_.set_friction(lag_friction(positions_at(q_, state.targets, state.progress)));
    state.iteration = 0;
    return Progress::kIterating;
  }
  if (hold_converged_) {
    state.held = true;
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

void Environment::finish_step() {
  const SimParameters& sim = model_->sim();
  const StepTargets& targets = step_->targets;
  const double h = sim.dt;
  v_ = (q_ - targets.q_start) / h;
  for (std::size_t b = 0; b < model_->bodies().size(); ++b) {
    if (model_->bodies()[b].type != BodyType::kKinematic) continue;
    kinematic_velocity_[b] = (targets.pose_target[b].position - poses_[b].position) / h;
    poses_[b] = targets.pose_target[b];
  }
  time_ += h;
  record_diagnostics(targets);
  if (sim.adaptive_kappa && diagnostics_.min_distance < 0.1 * sim.d_hat) kappa_ *= 2.0;
  ++statistics_.steps;
  step_.reset();
}

VertexContactForces Environment::vertex_contact_forces() const {
  const CollisionMesh& mesh = model_->collision();
  const Vertices x = collision_positions();
  VertexContactForces forces{Vertices::Zero(mesh.size(), 3), Vertices::Zero(mesh.size(), 3)};
  auto add = [](Vertices& to, const std::array<int, 4>& vertex,
                const Eigen::Matrix<double, 12, 1>& f) {
    for (int i = 0; i < 4; ++i) to.row(vertex[i]) += f.segment<3>(3 * i).transpose();
  };
  for (const ContactPair& pair : find_contact_pairs(*model_, x, x, model_->sim().d_hat)) {
    const ContactForce force = potential_.contact_force(pair, x);
    if (force.magnitude > 0.0) add(forces.normal, pair.vertex, force.force);
  }
  for (const FrictionContact& contact : potential_.friction()) {
    add(forces.friction, contact.vertex, potential_.friction_force(contact, x));
  }
  return forces;
}

void Environment::record_diagnostics(const StepTargets& targets) {
  const SimParameters& sim = model_->sim();
  const CollisionMesh& mesh = model_->collision();
  const Vertices x = positions_at(q_, targets, 1.0);
  diagnostics_.min_volume_ratio = min_volume_ratio();
  diagnostics_.friction_contacts = static_cast<int>(potential_.friction().size());
  std::map<std::pair<int, int>, PairForce> forces;
  // Adds the force on a stencil's vertices to the pair (side A's body, side B's body).
  auto add = [&](const std::array<int, 4>& vertex, bool edge_edge,
                 const Eigen::Matrix<double, 12, 1>& f, double normal) {
    const int side_a = mesh.vertex_body[vertex[0]];
    const int side_b = mesh.vertex_body[vertex[edge_edge ? 2 : 1]];
    if (side_a == side_b) return;  // self-contact: internal to the body
    const int first = std::min(side_a, side_b), second = std::max(side_a, side_b);
    PairForce& pf = forces[{first, second}];
    pf.body_a = first;
    pf.body_b = second;
    pf.normal_force += normal;
    for (int i = 0; i < 4; ++i) {
      if (mesh.vertex_body[vertex[i]] == first) pf.force += f.segment<3>(3 * i);
    }
  };
  for (const ContactPair& pair : find_contact_pairs(*model_, x, x, sim.d_hat)) {
    const ContactForce force = potential_.contact_force(pair, x);
    diagnostics_.min_distance = std::min(diagnostics_.min_distance, force.distance);
    if (force.magnitude > 0.0) add(pair.vertex, pair.edge_edge, force.force, force.magnitude);
  }
  for (const FrictionContact& contact : potential_.friction()) {
    add(contact.vertex, contact.edge_edge, potential_.friction_force(contact, x), 0.0);
  }
  for (const auto& [key, pf] : forces) diagnostics_.contact_forces.push_back(pf);
}

}  // namespace grip::solver
