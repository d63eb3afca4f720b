#pragma once
// A body that follows a script: a gripper link, a jaw, the ground. It has no DOFs; its state is
// a pose (and the velocity of its frame over the last step), and its rest vertices are in the
// body frame of the description.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "solver/scene.hpp"

namespace grip::solver::kinematic {

// Where the script puts the body at `next_time`, from `current` at next_time - h.
Pose advance(const Script& script, const Pose& current, double next_time, double h);

inline Eigen::Vector3d apply(const Pose& pose, const Eigen::Vector3d& point) {
  return pose.rotation * point + pose.position;
}

// Moves the pose (and turns the velocity) rigidly by `motion`.
void place(const Eigen::Isometry3d& motion, Pose& pose, Eigen::Vector3d& velocity);

}  // namespace grip::solver::kinematic
