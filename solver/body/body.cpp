#include "solver/body/body.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <stdexcept>

#include "solver/body/affine_body.hpp"
#include "solver/body/fem_body.hpp"
#include "solver/body/kinematic_body.hpp"

namespace grip::solver {

void invalid_body(const BodyDescription& body, const std::string& problem) {
  throw std::invalid_argument("body '" + body.name + "': " + problem);
}

Eigen::Matrix3d nearest_rotation(const Eigen::Matrix3d& m) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  d(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
  return svd.matrixU() * d * svd.matrixV().transpose();
}

void build_body(const BodyDescription& description, BodyModel& body) {
  switch (body.type) {
    case BodyType::kFem:
      return fem::build(description, body);
    case BodyType::kAffine:
      return affine::build(description, body);
    case BodyType::kKinematic:
      body.rest = description.vertices;
      body.dof_count = 0;
      return;
  }
}

void initial_body_state(const BodyModel& body, int index, const BodyDescription& description,
                        State& state) {
  state.poses[index] = description.pose;
  state.scripts[index] = description.script;
  state.kinematic_velocity[index] =
      description.script.keyframes.empty() ? description.script.velocity : Eigen::Vector3d::Zero();
  switch (body.type) {
    case BodyType::kFem:
      return fem::initial_state(body, description, state.q, state.v);
    case BodyType::kAffine:
      return affine::initial_state(body, description, state.q, state.v);
    case BodyType::kKinematic:
      return;
  }
}

void place_body(const BodyModel& body, int index, const Eigen::Isometry3d& motion, State& state) {
  switch (body.type) {
    case BodyType::kFem:
      return fem::place(body, motion, state.q, state.v);
    case BodyType::kAffine:
      if (is_driven(body)) {
        kinematic::place(motion, state.poses[index], state.kinematic_velocity[index]);
      }
      return affine::place(body, motion, state.q, state.v);
    case BodyType::kKinematic:
      return kinematic::place(motion, state.poses[index], state.kinematic_velocity[index]);
  }
}

Eigen::Vector3d vertex_position(const BodyModel& body, const Eigen::VectorXd& q, const Pose& pose,
                                int vertex) {
  switch (body.type) {
    case BodyType::kFem:
      return fem::vertex_position(body, q, vertex);
    case BodyType::kAffine:
      return affine::vertex_position(body, q, vertex);
    case BodyType::kKinematic:
      break;
  }
  return kinematic::apply(pose, body.rest.row(vertex).transpose());
}

int block_size(const BodyModel& body) {
  switch (body.type) {
    case BodyType::kFem:
      return 3;
    case BodyType::kAffine:
      return 12;
    case BodyType::kKinematic:
      break;
  }
  return 0;
}

int vertex_block(const BodyModel& body, int vertex) {
  switch (body.type) {
    case BodyType::kFem:
      return body.dof_offset + 3 * vertex;
    case BodyType::kAffine:
      return body.dof_offset;
    case BodyType::kKinematic:
      break;
  }
  return -1;
}

Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 12> vertex_jacobian(const BodyModel& body,
                                                                   int vertex) {
  switch (body.type) {
    case BodyType::kFem:
      return Eigen::Matrix3d::Identity();
    case BodyType::kAffine:
      return affine::vertex_jacobian(body, vertex);
    case BodyType::kKinematic:
      break;
  }
  return Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 12>(3, 0);
}

double max_displacement(const BodyModel& body, const Eigen::VectorXd& dq) {
  switch (body.type) {
    case BodyType::kFem:
      return fem::max_displacement(body, dq);
    case BodyType::kAffine:
      return affine::max_displacement(body, dq);
    case BodyType::kKinematic:
      break;
  }
  return 0.0;
}

void add_gravity(const BodyModel& body, const Eigen::Vector3d& gravity, double h,
                 Eigen::VectorXd& q_tilde) {
  if (body.type == BodyType::kFem) fem::add_gravity(body, gravity, h, q_tilde);
  if (body.type == BodyType::kAffine && !is_driven(body)) {
    affine::add_gravity(body, gravity, h, q_tilde);
  }
}

void add_drive_energy(const BodyModel& body, const Eigen::VectorXd& q,
                      const Eigen::VectorXd& target, double& sum) {
  if (!is_driven(body)) return;
  const int o = body.dof_offset;
  const Vector12d dq = q.segment<12>(o) - target.segment<12>(o);
  sum += 0.5 * body.drive_stiffness / body_mass(body) * dq.dot(body.mass_matrix * dq);
}

void add_drive_derivatives(const BodyModel& body, const Eigen::VectorXd& q,
                           const Eigen::VectorXd& target, double scale, Eigen::VectorXd& gradient,
                           std::vector<Eigen::Triplet<double>>* hessian) {
  if (!is_driven(body)) return;
  const int o = body.dof_offset;
  const double s = scale * body.drive_stiffness / body_mass(body);
  gradient.segment<12>(o) += s * (body.mass_matrix * (q.segment<12>(o) - target.segment<12>(o)));
  if (!hessian) return;
  for (int i = 0; i < 12; ++i) {
    for (int j = 0; j <= i; ++j) hessian->emplace_back(o + i, o + j, s * body.mass_matrix(i, j));
  }
}

void set_drive_target(const BodyModel& body, const Pose& pose, Eigen::VectorXd& dofs) {
  affine::set_pose(body, pose, dofs);
}

double body_mass(const BodyModel& body) {
  switch (body.type) {
    case BodyType::kFem:
      return body.vertex_mass.sum();
    case BodyType::kAffine:
      return body.mass_matrix(0, 0);
    case BodyType::kKinematic:
      break;
  }
  return 0.0;
}

Eigen::Vector3d center_of_mass(const BodyModel& body, int index, const State& state) {
  switch (body.type) {
    case BodyType::kFem:
      return fem::mass_weighted_mean(body, state.q);
    case BodyType::kAffine:
      return affine::center_of_mass(body, state.q);
    case BodyType::kKinematic:
      break;
  }
  return state.poses[index].position;
}

Eigen::Vector3d center_of_mass_velocity(const BodyModel& body, int index, const State& state) {
  switch (body.type) {
    case BodyType::kFem:
      return fem::mass_weighted_mean(body, state.v);
    case BodyType::kAffine:
      return affine::center_of_mass(body, state.v);
    case BodyType::kKinematic:
      break;
  }
  return state.kinematic_velocity[index];
}

Eigen::Matrix3d body_rotation(const BodyModel& body, int index, const State& state) {
  switch (body.type) {
    case BodyType::kFem:
      return fem::rotation(body, state.q);
    case BodyType::kAffine:
      return affine::rotation(body, state.q);
    case BodyType::kKinematic:
      break;
  }
  return state.poses[index].rotation.toRotationMatrix();
}

double min_volume_ratio(const Model& model, const Eigen::VectorXd& q) {
  double ratio = 1.0;
  for (const BodyModel& body : model.bodies()) {
    if (body.type == BodyType::kFem) ratio = std::min(ratio, fem::min_volume_ratio(body, q));
  }
  return ratio;
}

void add_inertia_energy(const BodyModel& body, const Eigen::VectorXd& q,
                        const Eigen::VectorXd& q_tilde, double& sum) {
  if (body.type == BodyType::kFem) fem::add_inertia_energy(body, q, q_tilde, sum);
  if (body.type == BodyType::kAffine) affine::add_inertia_energy(body, q, q_tilde, sum);
}

void add_inertia_derivatives(const BodyModel& body, const Eigen::VectorXd& q,
                             const Eigen::VectorXd& q_tilde, double scale,
                             Eigen::VectorXd& gradient,
                             std::vector<Eigen::Triplet<double>>* hessian) {
  if (body.type == BodyType::kFem) {
    fem::add_inertia_derivatives(body, q, q_tilde, scale, gradient, hessian);
  }
  if (body.type == BodyType::kAffine) {
    affine::add_inertia_derivatives(body, q, q_tilde, scale, gradient, hessian);
  }
}

void add_elastic_energy(const BodyModel& body, const Eigen::VectorXd& q, double& sum) {
  if (body.type == BodyType::kFem) fem::add_elastic_energy(body, q, sum);
  if (body.type == BodyType::kAffine) affine::add_elastic_energy(body, q, sum);
}

void add_elastic_derivatives(const BodyModel& body, const Eigen::VectorXd& q, double scale,
                             Eigen::VectorXd& gradient,
                             std::vector<Eigen::Triplet<double>>* hessian) {
  if (body.type == BodyType::kFem) {
    fem::add_elastic_derivatives(body, q, scale, nullptr, gradient, hessian);
  }
  if (body.type == BodyType::kAffine) {
    affine::add_elastic_derivatives(body, q, scale, gradient, hessian);
  }
}

}  // namespace grip::solver
