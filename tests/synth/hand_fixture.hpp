#pragma once
// Shared set-up of the hand tests: the shipped right LEAP-style hand and a sphere object.
#include <memory>

#include "src/geometry/primitives.hpp"
#include "src/grippers/leap_hand.hpp"
#include "src/synth/prepared_hand.hpp"
#include "src/synth/prepared_object.hpp"

namespace grip::synth::testing {

inline const PreparedHand& right_hand() {
  static const PreparedHand hand = [] {
    const grippers::LeapHandFiles files = grippers::shipped_leap_hand(grippers::HandSide::kRight);
    return PreparedHand(grippers::load_hand_model(files.urdf, files.points));
  }();
  return hand;
}

// A sphere of radius 0.04 m centred at (0, 0, 0.04).
inline const PreparedObject& sphere_object() {
  static const PreparedObject object = [] {
    geometry::SurfaceMesh sphere = geometry::make_sphere(0.04, 40, 20);
    sphere.vertices.col(2).array() += 0.04;
    return PreparedObject(sphere);
  }();
  return object;
}

// A flat slab (0.6 x 0.6 x 0.05 m) whose top face lies at z = 0.04: points above it all have
// their closest point inside that face, so its normal does not jump under small motions.
inline const PreparedObject& slab_object() {
  static const PreparedObject object = [] {
    geometry::SurfaceMesh slab = geometry::make_box(Eigen::Vector3d(0.6, 0.6, 0.05));
    slab.vertices.col(2).array() += 0.015;
    return PreparedObject(slab);
  }();
  return object;
}

// The palm facing down onto the sphere's top, its grasp point `height` above the centre.
inline Eigen::Isometry3d palm_over_sphere(double height) {
  Eigen::Isometry3d base = Eigen::Isometry3d::Identity();
  base.linear() = Eigen::AngleAxisd(3.141592653589793, Eigen::Vector3d::UnitX()).toRotationMatrix();
  base.translation() =
      Eigen::Vector3d(0.0, 0.0, 0.04 + height) - base.linear() * Eigen::Vector3d(0.07, 0.0, 0.0);
  return base;
}

}  // namespace grip::synth::testing
