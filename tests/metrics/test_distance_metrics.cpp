#include "src/metrics/distance_metrics.hpp"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

#include "src/geometry/primitives.hpp"

namespace grip::metrics {
namespace {

// A 4 cm cube centred on the origin: the signed distance of (x, 0, 0) is 0.02 - |x| near a face.
geometry::SignedDistance cube() {
  return geometry::SignedDistance(geometry::make_box(Eigen::Vector3d::Constant(0.04)));
}

TEST(DistanceMetrics, GripperApartFromTheObject) {
  // Paper Fig. 5 left: no contact, D1 = 0 and D2 = the gripper-object distance.
  geometry::Vertices points(3, 3);
  points << 0.021, 0.0, 0.0,  //
      -0.025, 0.0, 0.0,       //
      0.0, 0.03, 0.0;
  const DistanceMetrics d = distance_metrics(cube(), points);
  EXPECT_EQ(d.d1, 0.0);
  EXPECT_NEAR(d.d2, 0.001, 1e-12);
}

TEST(DistanceMetrics, PenetratingGripper) {
  // Paper Fig. 5 right: penetration, D1 = D2 = the deepest point's depth.
  geometry::Vertices points(3, 3);
  points << 0.017, 0.0, 0.0,  //
      0.019, 0.0, 0.0,        //
      0.0, 0.03, 0.0;
  const DistanceMetrics d = distance_metrics(cube(), points);
  EXPECT_NEAR(d.d1, 0.003, 1e-12);
  EXPECT_NEAR(d.d2, 0.003, 1e-12);
}

// The metrics skip points that cannot be the deepest; the result must be the full evaluation's,
// bit for bit, for points all outside, some inside, and far and near mixed.
TEST(DistanceMetrics, SkippingPointsGivesTheFullEvaluationsResult) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const geometry::SignedDistance object(geometry::make_cylinder(0.02, 0.05, 24));
  for (const double spread : {0.021, 0.03, 0.2}) {
    for (int trial = 0; trial < 20; ++trial) {
      geometry::Vertices points(500, 3);
      for (Eigen::Index i = 0; i < points.rows(); ++i) {
        points.row(i) = spread * Eigen::RowVector3d(unit(rng), unit(rng), unit(rng));
      }
      const DistanceMetrics fast = distance_metrics(object, points);
      const DistanceMetrics full = distance_metrics(object.evaluate(points));
      EXPECT_EQ(fast.d1, full.d1) << "spread " << spread << " trial " << trial;
      EXPECT_EQ(fast.d2, full.d2) << "spread " << spread << " trial " << trial;
    }
  }
}

TEST(DistanceMetrics, FromSignedDistances) {
  EXPECT_EQ(distance_metrics(Eigen::Vector3d(-0.5, -0.2, -0.9)).d1, 0.0);
  EXPECT_EQ(distance_metrics(Eigen::Vector3d(-0.5, -0.2, -0.9)).d2, 0.2);
  EXPECT_EQ(distance_metrics(Eigen::Vector3d(-0.5, 0.3, -0.9)).d1, 0.3);
  EXPECT_THROW(distance_metrics(Eigen::VectorXd()), std::invalid_argument);
}

}  // namespace
}  // namespace grip::metrics
