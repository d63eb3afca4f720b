// Environment's read-only views of its state: positions, centres of mass, rotations, volumes
// and contact forces, between steps.
#include "solver/body/body.hpp"
#include "solver/environment.hpp"

namespace grip::solver {

Vertices Environment::collision_positions() const {
  return solver::collision_positions(*model_, state_.q, targets_at_rest(*model_, state_), 0.0);
}

Vertices Environment::body_vertices(int index) const {
  const BodyModel& body = model_->bodies()[index];
  Vertices x(body.rest.rows(), 3);
  for (Eigen::Index v = 0; v < body.rest.rows(); ++v) {
    x.row(v) = vertex_position(body, state_.q, state_.poses[index], static_cast<int>(v));
  }
  return x;
}

Eigen::Vector3d Environment::center_of_mass(int index) const {
  return solver::center_of_mass(model_->bodies()[index], index, state_);
}

Eigen::Vector3d Environment::center_of_mass_velocity(int index) const {
  return solver::center_of_mass_velocity(model_->bodies()[index], index, state_);
}

Eigen::Matrix3d Environment::rotation(int index) const {
  return body_rotation(model_->bodies()[index], index, state_);
}

double Environment::min_volume_ratio() const { return solver::min_volume_ratio(*model_, state_.q); }

VertexContactForces Environment::vertex_contact_forces() const {
  return solver::vertex_contact_forces(*model_, newton_.potential(), collision_positions());
}

}  // namespace grip::solver
