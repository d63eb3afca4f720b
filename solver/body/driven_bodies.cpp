#include "solver/body/driven_bodies.hpp"

#include "solver/body/kinematic_motion.hpp"

namespace grip::solver {

void DrivenBodies::build(const BodyDescription& description) {
  AffineBodies::build(description);
  drive_stiffness_.push_back(description.drive_stiffness);
}

void DrivenBodies::place(int i, const Eigen::Isometry3d& motion, State& state) const {
  kinematic::place(motion, state.poses[body(i)], state.kinematic_velocity[body(i)]);
  AffineBodies::place(i, motion, state);
}

void DrivenBodies::set_drive_target(int i, const Pose& pose, Eigen::VectorXd& dofs) const {
  set_pose(i, pose, dofs);
}

// k is the drive stiffness, m the body's mass, M its mass matrix.
void DrivenBodies::add_drive_energy(int i, const Eigen::VectorXd& q, const Eigen::VectorXd& target,
                                    double& sum) const {
  const int o = dof_offset(i);
  const Vector12d dq = q.segment<12>(o) - target.segment<12>(o);
  sum += 0.5 * drive_stiffness_[i] / mass(i) * dq.dot(mass_matrix(i) * dq);
}

void DrivenBodies::add_drive_derivatives(int i, const Eigen::VectorXd& q,
                                         const Eigen::VectorXd& target, double scale,
                                         Eigen::VectorXd& gradient, Triplets* hessian) const {
  const int o = dof_offset(i);
  const double s = scale * drive_stiffness_[i] / mass(i);
  gradient.segment<12>(o) += s * (mass_matrix(i) * (q.segment<12>(o) - target.segment<12>(o)));
  if (hessian) add_mass_triplets(i, s, *hessian);
}

}  // namespace grip::solver
