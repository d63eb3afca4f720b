#include "src/synth/prepared_object.hpp"

#include <numeric>
#include <vector>

#include <Eigen/Geometry>

namespace grip::synth {
namespace {

int find_root(std::vector<int>& parent, int v) {
  while (parent[static_cast<std::size_t>(v)] != v) {
    parent[static_cast<std::size_t>(v)] =
        parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(v)])];
    v = parent[static_cast<std::size_t>(v)];
  }
  return v;
}

}  // namespace

PreparedObject::PreparedObject(geometry::SurfaceMesh closed_surface)
    : surface_(std::move(closed_surface)),
      tree_(surface_),
      signed_distance_(std::make_shared<geometry::SignedDistance>(surface_)) {
  double area = 0.0;
  centroid_.setZero();
  for (int f = 0; f < surface_.triangles.rows(); ++f) {
    const Eigen::Vector3d a = surface_.vertices.row(surface_.triangles(f, 0));
    const Eigen::Vector3d b = surface_.vertices.row(surface_.triangles(f, 1));
    const Eigen::Vector3d c = surface_.vertices.row(surface_.triangles(f, 2));
    const double w = 0.5 * (b - a).cross(c - a).norm();
    area += w;
    centroid_ += w * (a + b + c) / 3.0;
  }
  centroid_ /= area;
  lower_ = surface_.vertices.colwise().minCoeff().transpose();
  upper_ = surface_.vertices.colwise().maxCoeff().transpose();
}

double PreparedObject::clearance(const geometry::SurfaceMesh& gripper, double cutoff) const {
  const TriangleTree::Proximity near = tree_.proximity(gripper, cutoff);
  if (near.intersecting) return 0.0;
  // No triangles cross, so each closed gripper component is wholly inside or wholly outside
  // the object, and the object wholly inside or outside each component: one vertex decides.
  const int n = static_cast<int>(gripper.vertices.rows());
  std::vector<int> parent(static_cast<std::size_t>(n));
  std::iota(parent.begin(), parent.end(), 0);
  for (int f = 0; f < gripper.triangles.rows(); ++f) {
    for (int k = 1; k < 3; ++k) {
      const int a = find_root(parent, gripper.triangles(f, 0));
      const int b = find_root(parent, gripper.triangles(f, k));
      parent[static_cast<std::size_t>(a)] = b;
    }
  }
  std::vector<Eigen::Vector3d> lower(static_cast<std::size_t>(n), Eigen::Vector3d::Constant(1e300));
  std::vector<Eigen::Vector3d> upper(static_cast<std::size_t>(n),
                                     Eigen::Vector3d::Constant(-1e300));
  std::vector<bool> used(static_cast<std::size_t>(n), false);
  for (int f = 0; f < gripper.triangles.rows(); ++f) {
    for (int k = 0; k < 3; ++k) used[static_cast<std::size_t>(gripper.triangles(f, k))] = true;
  }
  for (int v = 0; v < n; ++v) {
    if (!used[static_cast<std::size_t>(v)]) continue;
    const auto r = static_cast<std::size_t>(find_root(parent, v));
    const Eigen::Vector3d p = gripper.vertices.row(v);
    lower[r] = lower[r].cwiseMin(p);
    upper[r] = upper[r].cwiseMax(p);
  }
  for (int v = 0; v < n; ++v) {
    if (!used[static_cast<std::size_t>(v)] || find_root(parent, v) != v) continue;
    if ((*signed_distance_)(gripper.vertices.row(v).transpose()) >= 0.0) return 0.0;
    const auto r = static_cast<std::size_t>(v);
    if ((lower[r].array() <= lower_.array()).all() && (upper[r].array() >= upper_.array()).all()) {
      return 0.0;
    }
  }
  return near.distance;
}

}  // namespace grip::synth
