#pragma once
// Scripted motion of a pose: where a script puts a body frame (a kinematic body, a driven body's
// drive target), a point in that frame, and a rigid move of the frame.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "solver/scene/scene.hpp"

namespace grip::solver::kinematic {

// Where the script puts the body at `next_time`, from `current` at next_time - h.
Pose advance(const Script& script, const Pose& current, double next_time, double h);

inline Eigen::Vector3d apply(const Pose& pose, const Eigen::Vector3d& point) {
  return pose.rotation * point + pose.position;
}

// Moves the pose (and turns the velocity) rigidly by `motion`.
void place(const Eigen::Isometry3d& motion, Pose& pose, Eigen::Vector3d& velocity);

}  // namespace grip::solver::kinematic
