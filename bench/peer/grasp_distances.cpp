#include "bench/peer/grasp_distances.hpp"

#include <stdexcept>

namespace grip::bench {
namespace {

// Both fingers over their finger-frame vertices, as trial::TrialScene samples its D1/D2 points.
geometry::SurfaceMesh finger_pair(const grippers::ParallelGripper& gripper) {
  if (gripper.soft_finger) {
    throw std::invalid_argument("grip bench peer: soft fingers are not compared");
  }
  const geometry::SurfaceMesh& one = gripper.finger_surface;
  const Eigen::Index n = one.vertices.rows();
  geometry::SurfaceMesh both;
  both.vertices.resize(2 * n, 3);
  both.vertices << one.vertices, one.vertices;
  both.triangles.resize(2 * one.triangles.rows(), 3);
  both.triangles << one.triangles, (one.triangles.array() + static_cast<int>(n)).matrix();
  return both;
}

}  // namespace

GraspDistances::GraspDistances(const grippers::ParallelGripper& gripper,
                               const geometry::SurfaceMesh& object,
                               const trial::TrialParameters& parameters)
    : finger_(gripper.finger_surface.vertices),
      points_(finger_pair(gripper), parameters.metric_samples, parameters.metric_seed),
      object_(object) {}

metrics::DistanceMetrics GraspDistances::operator()(const std::array<Eigen::Isometry3d, 2>& fingers,
                                                    const Eigen::Isometry3d& object) const {
  const Eigen::Index n = finger_.rows();
  geometry::Vertices world(2 * n, 3);
  for (int j = 0; j < 2; ++j) {
    for (Eigen::Index v = 0; v < n; ++v) {
      world.row(j * n + v) = (fingers[j] * finger_.row(v).transpose()).transpose();
    }
  }
  const geometry::Vertices points = points_.positions(world);
  // Into the object frame, as trial::ObjectBody does for a rigid object.
  const Eigen::Matrix3d a_inverse = object.linear().inverse();
  geometry::Vertices local(points.rows(), 3);
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    local.row(i) = (a_inverse * (points.row(i).transpose() - object.translation())).transpose();
  }
  return metrics::distance_metrics(object_, local);
}

}  // namespace grip::bench
