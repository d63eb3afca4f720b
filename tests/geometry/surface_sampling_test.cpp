// Area-uniform surface sampling, checked by chi-square tests at significance 0.001 with fixed
// seeds (so each run is the same draw), plus normals and determinism.
#include "src/geometry/surface_sampling.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <array>

#include "src/geometry/mesh_measures.hpp"
#include "tests/geometry/test_meshes.hpp"

namespace grip::geometry {
namespace {

// Upper 0.001 quantiles of the chi-square distribution (standard tables).
constexpr double kChiSquare999Dof3 = 16.266;
constexpr double kChiSquare999Dof9 = 27.877;
constexpr double kChiSquare999Dof11 = 31.264;

TEST(GeometrySurfaceSamplingTest, FacesAreHitInProportionToTheirArea) {
  // Box faces of three very different areas.
  const SurfaceMesh box = testing::box(0.01, 0.03, 0.07);
  const int count = 60000;
  const SurfaceSamples samples = sample_surface(box, count, 11);
  std::array<int, 12> hits{};
  for (int i = 0; i < count; ++i) ++hits[static_cast<std::size_t>(samples.faces[i])];
  const double total = surface_area(box);
  double chi_square = 0.0;
  for (int f = 0; f < 12; ++f) {
    const Eigen::Vector3d a = box.vertices.row(box.triangles(f, 0));
    const Eigen::Vector3d b = box.vertices.row(box.triangles(f, 1));
    const Eigen::Vector3d c = box.vertices.row(box.triangles(f, 2));
    const double expected = count * 0.5 * (b - a).cross(c - a).norm() / total;
    chi_square += std::pow(hits[static_cast<std::size_t>(f)] - expected, 2) / expected;
  }
  EXPECT_LT(chi_square, kChiSquare999Dof11);
}

TEST(GeometrySurfaceSamplingTest, PointsAreUniformWithinATriangle) {
  SurfaceMesh triangle;
  triangle.vertices.resize(3, 3);
  triangle.vertices << 0, 0, 0, 1, 0, 0, 0.2, 1, 0;
  triangle.triangles.resize(1, 3);
  triangle.triangles << 0, 1, 2;
  const int count = 40000;
  const SurfaceSamples samples = sample_surface(triangle, count, 12);
  const Eigen::Matrix2d edges = (Eigen::Matrix2d() << 1, 0.2, 0, 1).finished();
  std::array<int, 4> quarter{};  // the midpoint subdivision: 4 triangles of equal area
  std::array<int, 10> strip{};   // strips 0.1 wide in the barycentric coordinate of corner 0
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector2d uv = edges.inverse() * samples.points.row(i).head<2>().transpose();
    const double l0 = 1.0 - uv.x() - uv.y();
    ASSERT_GE(l0, -1e-12);
    ASSERT_GE(uv.minCoeff(), -1e-12);
    ASSERT_EQ(samples.points(i, 2), 0.0);
    ++quarter[l0 > 0.5 ? 0 : uv.x() > 0.5 ? 1 : uv.y() > 0.5 ? 2 : 3];
    ++strip[static_cast<std::size_t>(std::min(9, static_cast<int>(l0 * 10)))];
  }
  double chi_quarter = 0.0;
  for (int hits : quarter) chi_quarter += std::pow(hits - count / 4.0, 2) / (count / 4.0);
  EXPECT_LT(chi_quarter, kChiSquare999Dof3);
  // The strip a <= l0 < b holds the fraction (1 - a)^2 - (1 - b)^2 of the area.
  double chi_strip = 0.0;
  for (int k = 0; k < 10; ++k) {
    const double expected = count * (std::pow(1 - 0.1 * k, 2) - std::pow(1 - 0.1 * (k + 1), 2));
    chi_strip += std::pow(strip[static_cast<std::size_t>(k)] - expected, 2) / expected;
  }
  EXPECT_LT(chi_strip, kChiSquare999Dof9);
}

TEST(GeometrySurfaceSamplingTest, NormalsAreOutwardUnitFaceNormals) {
  const SurfaceMesh box = testing::box(0.01, 0.03, 0.07);
  const SurfaceSamples samples = sample_surface(box, 1000, 13);
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Vector3d n = samples.normals.row(i);
    const Eigen::Vector3d p = samples.points.row(i);
    ASSERT_NEAR(n.norm(), 1.0, 1e-12);
    // On a box centred at the origin the outward normal points away from the centre.
    ASSERT_GT(n.dot(p), 0.0);
  }
}

TEST(GeometrySurfaceSamplingTest, SameSeedSameSamplesOtherSeedOthers) {
  const SurfaceMesh sphere = testing::uv_sphere(0.05, 8, 16);
  const SurfaceSamples a = sample_surface(sphere, 500, 7);
  const SurfaceSamples b = sample_surface(sphere, 500, 7);
  const SurfaceSamples c = sample_surface(sphere, 500, 8);
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.faces, b.faces);
  EXPECT_NE(a.points, c.points);
}

TEST(GeometrySurfaceSamplingTest, ZeroAreaIsAnError) {
  SurfaceMesh degenerate = testing::box(0.01, 0.01, 0.01);
  degenerate.vertices.setZero();
  EXPECT_THROW(sample_surface(degenerate, 10, 1), std::invalid_argument);
}

}  // namespace
}  // namespace grip::geometry
