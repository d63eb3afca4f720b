#include "src/metrics/distance_metrics.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

namespace grip::metrics {

DistanceMetrics distance_metrics(const Eigen::VectorXd& signed_distances) {
  if (signed_distances.size() == 0) {
    throw std::invalid_argument("D1/D2 need at least one gripper surface point");
  }
  const double deepest = signed_distances.maxCoeff();
  return {std::max(0.0, deepest), std::abs(deepest)};
}

// Only the deepest point counts, so the points are visited from the one that could lie deepest,
// judged by the object's bounding box: a point outside it by b lies at least b from the object
// (signed distance <= -b); a point inside it may lie anywhere. Once no remaining point can beat
// the deepest so far, the rest are skipped: the result is the full evaluation's, exactly.
DistanceMetrics distance_metrics(const geometry::SignedDistance& object,
                                 const geometry::Vertices& gripper_points) {
  const Eigen::Index n = gripper_points.rows();
  if (n == 0) return distance_metrics(Eigen::VectorXd());
  // upper[i]: the most point i's signed distance can be.
  const Eigen::Matrix<double, 2, 3> box = object.bounds();
  Eigen::VectorXd upper(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::RowVector3d p = gripper_points.row(i);
    const double outside = (box.row(0) - p).cwiseMax(p - box.row(1)).cwiseMax(0.0).norm();
    upper[i] = outside > 0.0 ? -outside : std::numeric_limits<double>::infinity();
  }
  Eigen::Index first = 0;
  upper.maxCoeff(&first);
  double deepest = object(gripper_points.row(first).transpose());
  // The points that could still lie deeper, most promising first.
  std::vector<std::pair<double, Eigen::Index>> rest;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (i != first && upper[i] > deepest) rest.emplace_back(upper[i], i);
  }
  std::sort(rest.begin(), rest.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first > b.first : a.second < b.second;
  });
  for (const auto& [bound, i] : rest) {
    if (bound <= deepest) break;
    deepest = std::max(deepest, object(gripper_points.row(i).transpose()));
  }
  return {std::max(0.0, deepest), std::abs(deepest)};
}

}  // namespace grip::metrics
