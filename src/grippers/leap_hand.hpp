#pragma once
// The LEAP-style 16-DoF hand shipped in assets/grippers/leap_right and leap_left: its
// generator (URDF, link meshes, contact candidates and keypoints) and where the shipped files are.
#include <filesystem>

namespace grip::grippers {

// The left hand is the right hand mirrored through its x-z plane (y -> -y), with mirrored
// joint axes, so equal joint values give mirrored poses.
enum class HandSide { kRight, kLeft };

// Hand frame (the palm link): +x points from the wrist to the fingers, +z out of the palm (the
// grasping side), y = z cross x; the right thumb sits at -y. The palm is a 0.10 x 0.09 x 0.03 m
// box with its grasping face at z = 0. Four fingers (index, middle, ring, thumb) of four
// revolute joints each, with the real LEAP Hand's joint limits; positive flexion curls a
// finger towards its pad (+z of its links). Links (palm, then <finger>_knuckle, _proximal,
// _intermediate, _distal) are boxes and capsules of our own design.
// Degrees of freedom, in order: index_abd, index_mcp, index_pip, index_dip, middle_* (same),
// ring_* (same), thumb_rot, thumb_abd, thumb_mcp, thumb_ip.
struct LeapHandFiles {
  std::filesystem::path urdf;    // <folder>/<name>.urdf, name = leap_right or leap_left
  std::filesystem::path points;  // <folder>/hand_points.toml
};

// Writes the hand into `folder` (created if missing): the URDF, meshes/*.obj and the hand
// points (15 contact candidates per fingertip, keypoint spheres on every link). Deterministic:
// the shipped assets are this function's output (see docs/assets.md to regenerate them).
LeapHandFiles write_leap_hand(const std::filesystem::path& folder, HandSide side);

// The shipped files of one side, under gripper_asset_dir().
LeapHandFiles shipped_leap_hand(HandSide side);

// The folder holding the shipped gripper assets: $GRIP_ASSET_DIR/grippers when that variable
// is set, else the source tree's assets/grippers.
std::filesystem::path gripper_asset_dir();

}  // namespace grip::grippers
