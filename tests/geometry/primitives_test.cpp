#include "src/geometry/primitives.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "src/geometry/mesh_measures.hpp"
#include "src/grippers/surface_merge.hpp"
#include "tests/grippers/mesh_checks.hpp"

namespace grip::geometry {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(GrippersPrimitives, BoxIsClosedOutwardAndExact) {
  const geometry::SurfaceMesh box = make_box(Eigen::Vector3d(0.1, 0.02, 0.03));
  EXPECT_TRUE(grippers::testing::is_closed_and_oriented(box));
  EXPECT_EQ(grippers::testing::euler_characteristic(box), 2);
  EXPECT_NEAR(geometry::surface_volume(box), 0.1 * 0.02 * 0.03, 1e-18);
  EXPECT_NEAR(geometry::surface_area(box), 2 * (0.1 * 0.02 + 0.1 * 0.03 + 0.02 * 0.03), 1e-15);
}

// A polyhedron inscribed in a round solid: its volume is a little below the solid's and
// approaches it as the facets shrink.
TEST(GrippersPrimitives, CapsuleApproachesTheRoundSolidFromInside) {
  const double r = 0.01, length = 0.05;
  const double exact = kPi * r * r * (length - 2 * r) + 4.0 / 3.0 * kPi * r * r * r;
  double previous_error = 1.0;
  for (const int segments : {12, 24, 48, 96}) {
    const geometry::SurfaceMesh capsule = make_capsule(r, length, segments, segments / 4);
    EXPECT_TRUE(grippers::testing::is_closed_and_oriented(capsule));
    EXPECT_EQ(grippers::testing::euler_characteristic(capsule), 2);
    const double error = (exact - geometry::surface_volume(capsule)) / exact;
    EXPECT_GT(error, 0.0);
    EXPECT_LT(error, previous_error);
    previous_error = error;
    EXPECT_NEAR(capsule.vertices.col(0).minCoeff(), 0.0, 1e-15);
    EXPECT_NEAR(capsule.vertices.col(0).maxCoeff(), length, 1e-15);
  }
  EXPECT_LT(previous_error, 2e-3);
}

TEST(GrippersPrimitives, CylinderAndSphereAreClosedAndCentred) {
  const geometry::SurfaceMesh cylinder = make_cylinder(0.02, 0.1, 64);
  EXPECT_TRUE(grippers::testing::is_closed_and_oriented(cylinder));
  EXPECT_NEAR(cylinder.vertices.col(2).minCoeff(), -0.05, 1e-15);
  EXPECT_NEAR(cylinder.vertices.col(2).maxCoeff(), 0.05, 1e-15);
  // A prism over a regular 64-gon: exact volume (n/2) r^2 sin(2 pi / n) h.
  EXPECT_NEAR(geometry::surface_volume(cylinder), 32 * 0.02 * 0.02 * std::sin(2 * kPi / 64) * 0.1,
              1e-15);
  const geometry::SurfaceMesh sphere = make_sphere(0.03, 48, 12);
  EXPECT_TRUE(grippers::testing::is_closed_and_oriented(sphere));
  EXPECT_NEAR(sphere.vertices.rowwise().norm().maxCoeff(), 0.03, 1e-15);
  EXPECT_NEAR(geometry::surface_volume(sphere), 4.0 / 3.0 * kPi * 0.027e-3, 0.01 * 1.13e-4);
}

TEST(GrippersPrimitives, MirroredAppendKeepsFacesOutward) {
  const geometry::SurfaceMesh capsule = make_capsule(0.01, 0.04, 24, 6);
  geometry::SurfaceMesh mirrored;
  grippers::append_transformed(mirrored, capsule, Eigen::Affine3d(Eigen::Scaling(1.0, -1.0, 1.0)));
  EXPECT_TRUE(grippers::testing::is_closed_and_oriented(mirrored));
  EXPECT_NEAR(geometry::surface_volume(mirrored), geometry::surface_volume(capsule), 1e-18);
}

TEST(GrippersPrimitives, RejectDegenerateSizes) {
  EXPECT_THROW(make_box(Eigen::Vector3d(0.1, 0.0, 0.1)), std::invalid_argument);
  EXPECT_THROW(make_capsule(0.02, 0.03, 24, 4), std::invalid_argument);
  EXPECT_THROW(make_capsule(0.01, 0.03, 2, 4), std::invalid_argument);
  EXPECT_THROW(make_cylinder(0.0, 0.1, 24), std::invalid_argument);
}

}  // namespace
}  // namespace grip::geometry
