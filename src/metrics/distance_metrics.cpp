#include "src/metrics/distance_metrics.hpp"

#include <algorithm>
#include <stdexcept>

namespace grip::metrics {

DistanceMetrics distance_metrics(const Eigen::VectorXd& signed_distances) {
  if (signed_distances.size() == 0) {
    throw std::invalid_argument("D1/D2 need at least one gripper surface point");
  }
  const double deepest = signed_distances.maxCoeff();
  return {std::max(0.0, deepest), std::abs(deepest)};
}

DistanceMetrics distance_metrics(const geometry::SignedDistance& object,
                                 const geometry::Vertices& gripper_points) {
  return distance_metrics(object.evaluate(gripper_points));
}

}  // namespace grip::metrics
