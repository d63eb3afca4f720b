// Swept surfaces against the closed-form volumes of their polygonal approximations.
#include "src/objects/surface_of_revolution.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "src/geometry/mesh_measures.hpp"

namespace grip::objects {
namespace {

constexpr double kPi = std::numbers::pi;

// A revolved profile with n segments is a stack of prisms over regular n-gons: area of an
// n-gon of circumradius r is n/2 r^2 sin(2 pi / n).
double polygon_area(double r, int n) { return 0.5 * n * r * r * std::sin(2 * kPi / n); }

TEST(ObjectsSurfaceOfRevolutionTest, RevolvedRectangleIsAPrismOverAPolygon) {
  const int n = 24;
  const geometry::SurfaceMesh mesh =
      revolve_profile({{0.0, 0.0}, {0.03, 0.0}, {0.03, 0.1}, {0.0, 0.1}}, n, false);
  EXPECT_NEAR(geometry::surface_volume(mesh), polygon_area(0.03, n) * 0.1, 1e-15);
  EXPECT_EQ(mesh.vertices.rows(), 2 + 2 * n);
}

TEST(ObjectsSurfaceOfRevolutionTest, ProfileDirectionDoesNotChangeOrientation) {
  const geometry::SurfaceMesh up =
      revolve_profile({{0.0, 0.0}, {0.03, 0.0}, {0.03, 0.1}, {0.0, 0.1}}, 16, false);
  const geometry::SurfaceMesh down =
      revolve_profile({{0.0, 0.1}, {0.03, 0.1}, {0.03, 0.0}, {0.0, 0.0}}, 16, false);
  EXPECT_NEAR(geometry::surface_volume(up), geometry::surface_volume(down), 1e-15);
  EXPECT_GT(geometry::surface_volume(down), 0.0);
}

TEST(ObjectsSurfaceOfRevolutionTest, TorusLoopAndTube) {
  // Revolving a square loop (a washer) with n segments: outer minus inner prism.
  const int n = 32;
  const geometry::SurfaceMesh washer =
      revolve_profile({{0.02, 0.0}, {0.04, 0.0}, {0.04, 0.01}, {0.02, 0.01}}, n, true);
  EXPECT_NEAR(geometry::surface_volume(washer),
              (polygon_area(0.04, n) - polygon_area(0.02, n)) * 0.01, 1e-15);

  // A straight tube is a prism over a regular polygon of the tube radius.
  const geometry::SurfaceMesh tube = sweep_tube(
      {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.05, 0.05, 0), Eigen::Vector3d(0.1, 0.1, 0)},
      0.01, n);
  EXPECT_NEAR(geometry::surface_volume(tube), polygon_area(0.01, n) * 0.1 * std::sqrt(2.0), 1e-15);
}

TEST(ObjectsSurfaceOfRevolutionTest, RejectsProfilesOffTheAxis) {
  EXPECT_THROW(revolve_profile({{0.01, 0.0}, {0.03, 0.0}, {0.0, 0.1}}, 16, false),
               std::invalid_argument);
  EXPECT_THROW(revolve_profile({{0.0, 0.0}, {0.03, 0.0}, {0.0, 0.1}}, 16, true),
               std::invalid_argument);
}

}  // namespace
}  // namespace grip::objects
