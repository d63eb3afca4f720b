// Tests of the convex hull's planes: a box's six faces, exits along axes and diagonals, and
// planes that come out the same on every construction (CGAL's own facet order varies).
#include <gtest/gtest.h>

#include <cmath>

#include "src/geometry/primitives.hpp"
#include "src/synth/convex_hull.hpp"

namespace grip::synth {
namespace {

TEST(SynthConvexHullTest, BoxHasSixPlanesAndExactExits) {
  geometry::SurfaceMesh box = geometry::make_box(Eigen::Vector3d(0.2, 0.1, 0.04));
  box.vertices.rowwise() += Eigen::RowVector3d(1.0, 2.0, 3.0);
  const ConvexHull hull(box.vertices);
  EXPECT_EQ(hull.planes().size(), 6u);
  EXPECT_TRUE(hull.centre().isApprox(Eigen::Vector3d(1.0, 2.0, 3.0), 1e-15));
  const ConvexHull::Exit x = hull.exit(Eigen::Vector3d::UnitX());
  EXPECT_TRUE(x.point.isApprox(Eigen::Vector3d(1.1, 2.0, 3.0), 1e-14));
  EXPECT_TRUE(x.normal.isApprox(Eigen::Vector3d::UnitX(), 1e-14));
  // Along (1, 1, 1) the ray meets z = 3.02 first (0.02 < 0.05 < 0.1).
  const ConvexHull::Exit d = hull.exit(Eigen::Vector3d(1, 1, 1));
  EXPECT_TRUE(d.point.isApprox(Eigen::Vector3d(1.02, 2.02, 3.02), 1e-14));
  EXPECT_TRUE(d.normal.isApprox(Eigen::Vector3d::UnitZ(), 1e-14));
}

TEST(SynthConvexHullTest, NonConvexShapeExitsOnItsHullAndIsReproducible) {
  // An L-shaped point set: the hull's diagonal facet bridges the notch.
  geometry::Vertices points(12, 3);
  points << 0, 0, 0, 2, 0, 0, 2, 1, 0, 1, 1, 0, 1, 2, 0, 0, 2, 0, 0, 0, 1, 2, 0, 1, 2, 1, 1, 1, 1,
      1, 1, 2, 1, 0, 2, 1;
  const ConvexHull a(points), b(points);
  ASSERT_EQ(a.planes().size(), b.planes().size());
  for (std::size_t i = 0; i < a.planes().size(); ++i) {
    EXPECT_EQ(a.planes()[i].normal, b.planes()[i].normal);
    EXPECT_EQ(a.planes()[i].offset, b.planes()[i].offset);
  }
  const ConvexHull::Exit e = a.exit(Eigen::Vector3d(1, 1, 0));
  EXPECT_TRUE(e.normal.isApprox(Eigen::Vector3d(1, 1, 0).normalized(), 1e-14));
  EXPECT_NEAR(e.point.x() + e.point.y(), 3.0, 1e-14);  // on the bridging plane x + y = 3
  EXPECT_THROW(ConvexHull(geometry::Vertices::Zero(4, 3)), std::invalid_argument);
}

}  // namespace
}  // namespace grip::synth
