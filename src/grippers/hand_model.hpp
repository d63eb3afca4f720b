#pragma once
// A dexterous hand as grasp synthesis uses it: kinematics and link surfaces from URDF, plus the
// contact candidates and self-penetration keypoints attached to its links.
#include <filesystem>

#include "src/grippers/hand_points.hpp"
#include "src/grippers/kinematic_tree.hpp"

namespace grip::grippers {

struct HandModel {
  KinematicTree kinematics;
  HandPoints points;
};

// Loads a hand's URDF and its points file; throws std::runtime_error naming the points file if
// a point refers to a link the URDF lacks.
HandModel load_hand_model(const std::filesystem::path& urdf, const std::filesystem::path& points);

}  // namespace grip::grippers
