// The exact signed distance (positive inside) against closed forms: an axis-aligned box, and a
// sphere's inscribed polyhedron (exact inside; within the tessellation gap of the sphere).
#include "src/geometry/signed_distance.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <random>

#include "tests/geometry/test_meshes.hpp"

namespace grip::geometry {
namespace {

// Positive inside, as SignedDistance: minus the usual box SDF.
double analytic_box(const Eigen::Vector3d& p, const Eigen::Vector3d& half) {
  const Eigen::Vector3d q = p.cwiseAbs() - half;
  return -(q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0));
}

Vertices random_points(int count, double extent, unsigned seed) {
  std::mt19937_64 generator(seed);
  std::uniform_real_distribution<double> uniform(-extent, extent);
  Vertices points(count, 3);
  for (int i = 0; i < count; ++i)
    points.row(i) << uniform(generator), uniform(generator), uniform(generator);
  return points;
}

TEST(GeometrySignedDistanceTest, MatchesAnalyticBoxInsideAndOutside) {
  const Eigen::Vector3d half(0.05, 0.03, 0.02);
  const SignedDistance distance(testing::box(half.x(), half.y(), half.z()));
  const Vertices points = random_points(4000, 0.1, 1);
  int inside = 0;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Eigen::Vector3d p = points.row(i);
    const double expected = analytic_box(p, half);
    inside += expected > 0;
    ASSERT_NEAR(distance(p), expected, 1e-9) << "at " << p.transpose();
  }
  EXPECT_GT(inside, 50) << "the test must probe the inside too";
  EXPECT_NEAR(distance(Eigen::Vector3d::Zero()), 0.02, 1e-12);
  EXPECT_NEAR(distance(Eigen::Vector3d(0.05, 0.0, 0.0)), 0.0, 1e-12);
}

TEST(GeometrySignedDistanceTest, InsideConvexPolyhedronIsTheNearestFacePlane) {
  const double radius = 0.05;
  const SurfaceMesh sphere = testing::uv_sphere(radius, 10, 20);
  const SignedDistance distance(sphere);
  // Face planes n . x = d with outward unit n.
  std::vector<std::pair<Eigen::Vector3d, double>> planes;
  double nearest_plane = radius;
  for (Eigen::Index f = 0; f < sphere.triangles.rows(); ++f) {
    const Eigen::Vector3d a = sphere.vertices.row(sphere.triangles(f, 0));
    const Eigen::Vector3d b = sphere.vertices.row(sphere.triangles(f, 1));
    const Eigen::Vector3d c = sphere.vertices.row(sphere.triangles(f, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
    planes.emplace_back(n, n.dot(a));
    nearest_plane = std::min(nearest_plane, n.dot(a));
  }
  const Vertices points = random_points(3000, radius, 2);
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Eigen::Vector3d p = points.row(i);
    if (p.norm() > 0.8 * nearest_plane) continue;  // strictly inside the polyhedron
    double expected = std::numeric_limits<double>::infinity();
    for (const auto& [n, d] : planes) expected = std::min(expected, d - n.dot(p));
    ASSERT_NEAR(distance(p), expected, 1e-9) << "at " << p.transpose();
  }
  // Against the true sphere: the polyhedron lies between radii nearest_plane and radius, so
  // the two distances differ by at most the gap radius - nearest_plane.
  const double gap = radius - nearest_plane;
  const Vertices far = random_points(3000, 2 * radius, 3);
  for (Eigen::Index i = 0; i < far.rows(); ++i) {
    const Eigen::Vector3d p = far.row(i);
    ASSERT_NEAR(distance(p), radius - p.norm(), gap + 1e-12) << "at " << p.transpose();
  }
}

TEST(GeometrySignedDistanceTest, BatchEqualsSingleQueriesAndClosestPointIsOnSurface) {
  const Eigen::Vector3d half(0.05, 0.03, 0.02);
  const SignedDistance distance(testing::box(half.x(), half.y(), half.z()));
  const Vertices points = random_points(2000, 0.1, 4);
  const Eigen::VectorXd batch = distance.evaluate(points);
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Eigen::Vector3d p = points.row(i);
    ASSERT_EQ(batch[i], distance(p));
    const Eigen::Vector3d q = distance.closest_point(p);
    ASSERT_NEAR((p - q).norm(), std::abs(batch[i]), 1e-12);
    ASSERT_NEAR(analytic_box(q, half), 0.0, 1e-12);
  }
}

TEST(GeometrySignedDistanceTest, RefusesOpenSurface) {
  SurfaceMesh open = testing::box(0.05, 0.05, 0.05);
  open.triangles.conservativeResize(10, 3);
  EXPECT_THROW(SignedDistance{open}, std::invalid_argument);
}

}  // namespace
}  // namespace grip::geometry
