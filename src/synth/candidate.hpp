#pragma once
// A synthesized grasp candidate as the trial consumes it: the gripper kind, one pose, joint
// values and contacts per hand, and the named energy terms that produced it.
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "src/grippers/gripper_registry.hpp"

namespace grip::synth {

struct HandGrasp {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // world from hand (gripper frame)
  Eigen::VectorXd joints;  // GripperType::joints: the opening (m), or the hand's joints (rad)
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> contacts;         // world, m
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> contact_normals;  // object's, outward
};

struct EnergyTerm {
  std::string name;
  double value = 0.0;
  bool operator==(const EnergyTerm&) const = default;
};

struct Candidate {
  grippers::GripperKind gripper = grippers::GripperKind::kFinRay;
  // One hand, or two for a bimanual grasp: the right hand (or first gripper) first.
  std::vector<HandGrasp> hands;
  std::vector<EnergyTerm> energies;  // the synthesizer's terms, documented in docs/synthesis.md
  double min_distance = 0.0;         // m, exact gripper-object distance at emission (capped)
};

// The dataset's pose layout: row-major 3x4 [R | t], world from hand.
std::vector<double> pose_row_major(const Eigen::Isometry3d& pose);

}  // namespace grip::synth
