#pragma once
// The bodies that follow a script exactly: gripper links, jaws, the ground. They have no DOFs;
// an environment's state holds each one's pose (and the velocity of its frame over the last
// step). Body i's rest vertices, in its description's frame, lie at
// [vertex_begin_[i], vertex_begin_[i + 1]) of one flat array.
#include <vector>

#include "solver/body/body_subsystem.hpp"

namespace grip::solver {

class KinematicBodies final : public BodySubsystem {
 public:
  KinematicBodies() : BodySubsystem(0) {}

  int dof_count(int /*i*/) const override { return 0; }
  bool scripted() const override { return true; }
  int vertex_count(int i) const override { return vertex_begin_[i + 1] - vertex_begin_[i]; }
  Eigen::Vector3d rest_vertex(int i, int v) const override { return rest_[vertex_begin_[i] + v]; }

  void place(int i, const Eigen::Isometry3d& motion, State& state) const override;
  // Its frame's origin stands for its centre of mass.
  Eigen::Vector3d center_of_mass(int i, const State& state) const override;
  Eigen::Vector3d center_of_mass_velocity(int i, const State& state) const override;
  Eigen::Matrix3d rotation(int i, const State& state) const override;
  void vertex_positions(int i, const Eigen::VectorXd& q, const Pose& pose,
                        std::span<const int> vertices, Vertices& out,
                        Eigen::Index first_row) const override;

 private:
  void build(const BodyDescription& description) override;

  std::vector<int> vertex_begin_{0};
  std::vector<Eigen::Vector3d> rest_;
};

}  // namespace grip::solver
