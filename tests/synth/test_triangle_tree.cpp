// Tests of TriangleTree and PreparedObject::clearance against analytic box distances and the
// brute-force check of exact_mesh_distance.hpp.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "src/geometry/primitives.hpp"
#include "src/synth/prepared_object.hpp"
#include "src/synth/triangle_tree.hpp"
#include "tests/synth/exact_mesh_distance.hpp"

namespace grip::synth {
namespace {

geometry::SurfaceMesh placed(geometry::SurfaceMesh mesh, const Eigen::Isometry3d& pose) {
  for (int v = 0; v < mesh.vertices.rows(); ++v) {
    mesh.vertices.row(v) = (pose * Eigen::Vector3d(mesh.vertices.row(v))).transpose();
  }
  return mesh;
}

Eigen::Isometry3d at(const Eigen::Vector3d& t, double turn_about_z = 0.0) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(turn_about_z, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  pose.translation() = t;
  return pose;
}

TEST(SynthTriangleTreeTest, FaceToFaceAndEdgeToFaceDistancesAreAnalytic) {
  const geometry::SurfaceMesh cube = geometry::make_box(Eigen::Vector3d::Constant(0.02));
  const TriangleTree tree(cube);
  // Face to face: a cube shifted 0.03 along x, offset sideways, leaves a 0.01 gap.
  const geometry::SurfaceMesh shifted = placed(cube, at({0.03, 0.004, 0.002}));
  EXPECT_NEAR(tree.proximity(shifted, 0.05).distance, 0.01, 1e-12);
  // Edge to face: turned 45 degrees about z, its nearest edge lies 0.01 sqrt(2) before its centre.
  const double d = 0.04;
  const geometry::SurfaceMesh turned = placed(cube, at({d, 0.0, 0.0}, std::numbers::pi / 4));
  const double expected = d - 0.01 * std::sqrt(2.0) - 0.01;
  const TriangleTree::Proximity p = tree.proximity(turned, 0.05);
  EXPECT_NEAR(p.distance, expected, 1e-12);
  EXPECT_FALSE(p.intersecting);
  EXPECT_NEAR(testing::brute_force_distance(cube, turned, 0.05), expected, 1e-12);
  // Beyond the cutoff the cutoff comes back.
  EXPECT_EQ(tree.proximity(turned, 0.001).distance, 0.001);
}

TEST(SynthTriangleTreeTest, OverlappingBoxesIntersect) {
  const geometry::SurfaceMesh cube = geometry::make_box(Eigen::Vector3d::Constant(0.02));
  const TriangleTree tree(cube);
  const TriangleTree::Proximity p =
      tree.proximity(placed(cube, at({0.015, 0.003, 0.0}, 0.3)), 0.01);
  EXPECT_TRUE(p.intersecting);
  EXPECT_EQ(p.distance, 0.0);
}

TEST(SynthTriangleTreeTest, ClosestPointAboveAFaceIsItsProjection) {
  const TriangleTree tree(geometry::make_box(Eigen::Vector3d::Constant(0.02)));
  const TriangleTree::Closest c = tree.closest({0.002, -0.003, 0.05});
  EXPECT_TRUE(c.point.isApprox(Eigen::Vector3d(0.002, -0.003, 0.01), 1e-12));
  EXPECT_NEAR(c.distance, 0.04, 1e-12);
  EXPECT_TRUE(tree.face_normal(c.face).isApprox(Eigen::Vector3d::UnitZ(), 1e-12));
}

TEST(SynthPreparedObjectTest, ClearanceIsZeroForContainmentEitherWay) {
  const PreparedObject object(geometry::make_box(Eigen::Vector3d::Constant(0.05)));
  // A small cube wholly inside the object: no triangle crosses, yet it penetrates.
  const geometry::SurfaceMesh inner = geometry::make_box(Eigen::Vector3d::Constant(0.01));
  EXPECT_FALSE(object.tree().proximity(inner, 0.01).intersecting);
  EXPECT_EQ(object.clearance(inner, 0.01), 0.0);
  // The object wholly inside a big gripper component.
  EXPECT_EQ(object.clearance(geometry::make_box(Eigen::Vector3d::Constant(0.2)), 0.01), 0.0);
  // A cube outside keeps its face-to-face gap.
  EXPECT_NEAR(object.clearance(placed(inner, at({0.035, 0.0, 0.0})), 0.01), 0.005, 1e-12);
  EXPECT_TRUE(object.centroid().isZero(1e-12));
}

}  // namespace
}  // namespace grip::synth
