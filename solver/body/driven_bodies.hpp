#pragma once
// The driven bodies: affine bodies pulled by a spring inside the step towards the pose their
// script gives (BodyDescription::drive_stiffness > 0), as a position-controlled drive with
// compliance would; gravity does not act on them (the drive carries their weight). A hand's
// finger links in a trial.
#include <vector>

#include "solver/body/affine_bodies.hpp"

namespace grip::solver {

class DrivenBodies final : public AffineBodies {
 public:
  bool scripted() const override { return true; }
  // The drive target turns with the body.
  void place(int i, const Eigen::Isometry3d& motion, State& state) const override;
  void add_gravity(int /*i*/, const Eigen::Vector3d& /*gravity*/, double /*h*/,
                   Eigen::VectorXd& /*q_tilde*/) const override {}

  void set_drive_target(int i, const Pose& pose, Eigen::VectorXd& dofs) const override;
  void add_drive_energy(int i, const Eigen::VectorXd& q, const Eigen::VectorXd& target,
                        double& sum) const override;
  void add_drive_derivatives(int i, const Eigen::VectorXd& q, const Eigen::VectorXd& target,
                             double scale, Eigen::VectorXd& gradient,
                             Triplets* hessian) const override;
  double drive_stiffness(int i) const { return drive_stiffness_[static_cast<std::size_t>(i)]; }

 private:
  void build(const BodyDescription& description) override;

  std::vector<double> drive_stiffness_;  // per body, N/m
};

}  // namespace grip::solver
