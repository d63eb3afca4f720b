#include "solver/body/kinematic_motion.hpp"

#include <vector>

namespace grip::solver::kinematic {
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

}  // namespace

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

void place(const Eigen::Isometry3d& motion, Pose& pose, Eigen::Vector3d& velocity) {
  const Eigen::Matrix3d r = motion.linear();
  pose.position = r * pose.position + motion.translation();
  pose.rotation = Eigen::Quaterniond(r) * pose.rotation;
  pose.rotation.normalize();
  velocity = r * velocity;
}

}  // namespace grip::solver::kinematic
