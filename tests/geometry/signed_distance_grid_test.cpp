// The cached grid: exact at its nodes, within its stated bound between them, exact outside.
#include "src/geometry/signed_distance_grid.hpp"

#include <gtest/gtest.h>

#include <random>

#include "tests/geometry/test_meshes.hpp"

namespace grip::geometry {
namespace {

TEST(GeometrySignedDistanceGridTest, WithinTheLipschitzBoundOfTheExactDistance) {
  auto exact = std::make_shared<const SignedDistance>(testing::uv_sphere(0.05, 16, 32));
  const SignedDistanceGrid grid(exact, 0.004, 0.01);
  std::mt19937_64 generator(5);
  std::uniform_real_distribution<double> uniform(-0.06, 0.06);
  double worst = 0.0;
  for (int i = 0; i < 5000; ++i) {
    const Eigen::Vector3d p(uniform(generator), uniform(generator), uniform(generator));
    ASSERT_TRUE(grid.contains(p));
    worst = std::max(worst, std::abs(grid(p) - (*exact)(p)));
  }
  EXPECT_LE(worst, grid.error_bound());
  EXPECT_GT(worst, 0.0) << "interpolation is not the exact path";
}

TEST(GeometrySignedDistanceGridTest, ExactAtNodesAndOutside) {
  auto exact = std::make_shared<const SignedDistance>(testing::box(0.05, 0.03, 0.02));
  const SignedDistanceGrid grid(exact, 0.01, 0.005);
  const Eigen::Vector3d origin =
      exact->bounds().row(0).transpose() - Eigen::Vector3d::Constant(0.005);
  for (int i = 0; i < grid.node_counts().x(); i += 3) {
    for (int j = 0; j < grid.node_counts().y(); j += 2) {
      const Eigen::Vector3d node = origin + 0.01 * Eigen::Vector3d(i, j, 2);
      EXPECT_NEAR(grid(node), (*exact)(node), 1e-12);
    }
  }
  const Eigen::Vector3d outside(0.3, 0.0, 0.0);
  EXPECT_FALSE(grid.contains(outside));
  EXPECT_EQ(grid(outside), (*exact)(outside));
}

TEST(GeometrySignedDistanceGridTest, RefusesBadSpacing) {
  auto exact = std::make_shared<const SignedDistance>(testing::box(0.05, 0.05, 0.05));
  EXPECT_THROW(SignedDistanceGrid(exact, 0.0, 0.0), std::invalid_argument);
  EXPECT_THROW(SignedDistanceGrid(exact, 1e-6, 0.0), std::invalid_argument);  // 1e15 nodes
}

}  // namespace
}  // namespace grip::geometry
