#pragma once
// A synthesized grasp candidate as the trial consumes it: the gripper kind, one pose, joint
// values and contacts per hand, and the named energy terms that produced it.
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace grip::synth {

// fin-ray: UMI-style soft fingers; parallel-jaw: rigid box fingers; leap: the 16-DoF hand.
enum class GripperKind { kFinRay, kParallelJaw, kLeap };

std::string_view gripper_name(GripperKind kind);
// Throws std::invalid_argument listing the known names.
GripperKind parse_gripper_kind(std::string_view name);
// Joint values per hand: 1 (the opening, m) for parallel grippers, 16 (rad) for the hand.
int joints_per_hand(GripperKind kind);

struct HandGrasp {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // world from hand (gripper frame)
  Eigen::VectorXd joints;                                  // see joints_per_hand
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> contacts;        // world, m
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> contact_normals;  // object's, outward
};

struct EnergyTerm {
  std::string name;
  double value = 0.0;
  bool operator==(const EnergyTerm&) const = default;
};

struct Candidate {
  GripperKind gripper = GripperKind::kFinRay;
  // One hand, or two for a bimanual grasp: the right hand (or first gripper) first.
  std::vector<HandGrasp> hands;
  std::vector<EnergyTerm> energies;  // the synthesizer's terms, documented in docs/synthesis.md
  double min_distance = 0.0;         // m, exact gripper-object distance at emission (capped)
};

// The dataset's pose layout: row-major 3x4 [R | t], world from hand.
std::vector<double> pose_row_major(const Eigen::Isometry3d& pose);

}  // namespace grip::synth
