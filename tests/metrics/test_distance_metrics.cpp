#include "src/metrics/distance_metrics.hpp"

#include <gtest/gtest.h>

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

TEST(DistanceMetrics, FromSignedDistances) {
  EXPECT_EQ(distance_metrics(Eigen::Vector3d(-0.5, -0.2, -0.9)).d1, 0.0);
  EXPECT_EQ(distance_metrics(Eigen::Vector3d(-0.5, -0.2, -0.9)).d2, 0.2);
  EXPECT_EQ(distance_metrics(Eigen::Vector3d(-0.5, 0.3, -0.9)).d1, 0.3);
  EXPECT_THROW(distance_metrics(Eigen::VectorXd()), std::invalid_argument);
}

}  // namespace
}  // namespace grip::metrics
