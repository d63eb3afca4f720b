#include "src/metrics/surface_points.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "src/geometry/primitives.hpp"

namespace grip::metrics {
namespace {

TEST(SurfacePoints, LieOnTheRestSurface) {
  const geometry::SurfaceMesh box = geometry::make_box(Eigen::Vector3d(0.02, 0.04, 0.06));
  const SurfacePoints points(box, 2000, 7);
  ASSERT_EQ(points.size(), 2000);
  const geometry::Vertices p = points.positions(box.vertices);
  for (Eigen::Index i = 0; i < p.rows(); ++i) {
    // On a box surface: inside the box and on at least one face plane.
    const Eigen::Array3d a = p.row(i).transpose().array().abs();
    const Eigen::Array3d half(0.01, 0.02, 0.03);
    EXPECT_TRUE((a <= half + 1e-12).all());
    EXPECT_LT((a - half).abs().minCoeff(), 1e-12);
  }
}

TEST(SurfacePoints, FollowAnAffineMotionOfTheVertices) {
  const geometry::SurfaceMesh box = geometry::make_box(Eigen::Vector3d(0.02, 0.04, 0.06));
  const SurfacePoints points(box, 500, 3);
  Eigen::Matrix3d a;
  a << 1.1, 0.2, 0.0, -0.1, 0.9, 0.3, 0.05, 0.0, 1.2;
  const Eigen::Vector3d t(0.3, -0.2, 0.1);
  const geometry::Vertices moved = ((box.vertices * a.transpose()).rowwise() + t.transpose());
  const geometry::Vertices expected =
      (points.positions(box.vertices) * a.transpose()).rowwise() + t.transpose();
  EXPECT_LT((points.positions(moved) - expected).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(SurfacePoints, SameSeedSamePoints) {
  const geometry::SurfaceMesh box = geometry::make_box(Eigen::Vector3d(0.02, 0.04, 0.06));
  EXPECT_EQ(SurfacePoints(box, 300, 11).positions(box.vertices),
            SurfacePoints(box, 300, 11).positions(box.vertices));
  EXPECT_NE(SurfacePoints(box, 300, 11).positions(box.vertices),
            SurfacePoints(box, 300, 12).positions(box.vertices));
}

}  // namespace
}  // namespace grip::metrics
