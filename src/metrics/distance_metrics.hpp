#pragma once
// GRIP's grasp quality metrics (paper, Sec. IV): with d_o(p) the object's signed distance,
// positive inside, over points p on the gripper surface,
//   D1 = max(0, max_p d_o(p))  (penetration depth),   D2 = |max_p d_o(p)|  (absolute distance).
#include <Eigen/Core>

#include "src/geometry/mesh.hpp"
#include "src/geometry/signed_distance.hpp"

namespace grip::metrics {

struct DistanceMetrics {
  double d1 = 0.0;  // m
  double d2 = 0.0;  // m
};

// From the signed distances of the gripper points. Throws std::invalid_argument when empty.
DistanceMetrics distance_metrics(const Eigen::VectorXd& signed_distances);

// Evaluates `object` (built on the object's surface in the frame the points are given in).
DistanceMetrics distance_metrics(const geometry::SignedDistance& object,
                                 const geometry::Vertices& gripper_points);

}  // namespace grip::metrics
