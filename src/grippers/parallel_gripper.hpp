#pragma once
// Two-finger parallel grippers on prismatic jaws: the UMI-style gripper with soft fin-ray
// fingers and a rigid parallel-jaw gripper with box fingers, and where their fingers sit.
#include <optional>
#include <string>

#include <Eigen/Geometry>

#include "src/geometry/mesh.hpp"
#include "src/grippers/fin_ray_finger.hpp"

namespace grip::grippers {

// Gripper frame: the origin lies midway between the two fingers' mount faces; +z is the
// approach axis (the fingers extend along +z, towards the object); +y is the closing axis: the
// kPositive finger sits at +y and closes towards -y, the kNegative finger mirrors it by a
// half turn about z; x = y cross z. The opening is the gap between the two contact faces
// (the finger frames' y = 0 planes), so each contact face lies at y = +-opening / 2.
enum class Jaw { kPositive, kNegative };

// Box fingers of the rigid gripper, in the finger-frame convention of FinRayOptions: x spans
// width centred on 0, y runs from the contact face (y = 0) to thickness, z from the mount
// (z = 0) to length.
struct RigidJawOptions {
  double width = 0.020;
  double thickness = 0.010;
  double length = 0.050;
};

// How the kNegative finger is made from the kPositive one, both in their finger frames: the
// same finger (finger_pose turns it half a turn about z), or its mirror image across the finger
// frame's x = 0 plane (turned so, the pair are mirror images across the gripper's y = 0 plane).
// The two agree for a finger symmetric across its width, as the built-in fingers are.
enum class SecondFinger { kSame, kMirrored };

struct ParallelGripper {
  std::string name;
  geometry::SurfaceMesh finger_surface;     // kPositive's finger, finger frame, closed, outward
  std::optional<FinRayFinger> soft_finger;  // its tet model when soft; empty if rigid
  SecondFinger second_finger = SecondFinger::kSame;
  double min_opening = 0.0;    // m
  double max_opening = 0.085;  // m
  // How deep the object must reach between the fingers, from their tips (synthesis' approach
  // depth), for the fingers to build the grip force before the jaws reach the end of their
  // stroke: 0 for rigid fingers; a fin-ray finger pressed nearer its tip wraps the object and
  // stops short of it (docs/synthesis.md, "Grasp depth").
  double min_grasp_depth = 0.0;  // m

  // Pose of a finger's frame in the gripper frame; throws std::out_of_range if `opening` lies
  // outside [min_opening, max_opening].
  Eigen::Isometry3d finger_pose(Jaw jaw, double opening) const;

  // Both fingers at `opening`, in the gripper frame.
  geometry::SurfaceMesh surface(double opening) const;
  // Both soft fingers' tet meshes at `opening`, kPositive's first, in the gripper frame; empty
  // for rigid fingers.
  geometry::TetMesh finger_tets(double opening) const;

  // Jaw `jaw`'s finger in its finger frame: its surface, and its tet model when soft (a mirrored
  // finger keeps the vertex numbering and the mount vertices of the kPositive one).
  geometry::SurfaceMesh finger_surface_of(Jaw jaw) const;
  std::optional<FinRayFinger> soft_finger_of(Jaw jaw) const;
};

// UMI-style: two fin-ray fingers (the surface is the tet mesh's boundary), jaw opening 0-85 mm,
// grasps at least 0.45 (solid fingers) or 0.75 (hollow ones) of the finger's length deep.
ParallelGripper make_umi_soft_gripper(const FinRayOptions& options = {});

// Two rigid box fingers on the same jaws, opening 0-85 mm.
ParallelGripper make_rigid_jaw_gripper(const RigidJawOptions& options = {});

}  // namespace grip::grippers
