#include "solver/body/kinematic_bodies.hpp"

#include "solver/body/kinematic_motion.hpp"

namespace grip::solver {

void KinematicBodies::build(const BodyDescription& description) {
  for (Eigen::Index v = 0; v < description.vertices.rows(); ++v) {
    rest_.push_back(description.vertices.row(v).transpose());
  }
  vertex_begin_.push_back(static_cast<int>(rest_.size()));
}

void KinematicBodies::place(int i, const Eigen::Isometry3d& motion, State& state) const {
  kinematic::place(motion, state.poses[body(i)], state.kinematic_velocity[body(i)]);
}

Eigen::Vector3d KinematicBodies::center_of_mass(int i, const State& state) const {
  return state.poses[body(i)].position;
}

Eigen::Vector3d KinematicBodies::center_of_mass_velocity(int i, const State& state) const {
  return state.kinematic_velocity[body(i)];
}

Eigen::Matrix3d KinematicBodies::rotation(int i, const State& state) const {
  return state.poses[body(i)].rotation.toRotationMatrix();
}

void KinematicBodies::vertex_positions(int i, const Eigen::VectorXd& /*q*/, const Pose& pose,
                                       std::span<const int> vertices, Vertices& out,
                                       Eigen::Index first_row) const {
  for (std::size_t k = 0; k < vertices.size(); ++k) {
    out.row(first_row + static_cast<Eigen::Index>(k)) =
        kinematic::apply(pose, rest_vertex(i, vertices[k]));
  }
}

}  // namespace grip::solver
