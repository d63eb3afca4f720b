#include "bench/peer/grasp_distances.hpp"

#include <stdexcept>

#include "src/geometry/boundary_surface.hpp"

namespace grip::bench {
namespace {

// Both fingers over their finger-frame surface vertices (a soft finger's: its tet mesh's
// boundary), as trial::ParallelTrialScene samples its D1/D2 points.
geometry::SurfaceMesh finger_pair(const grippers::ParallelGripper& gripper) {
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
    : parts_{gripper.finger_surface.vertices, gripper.finger_surface.vertices},
      points_(finger_pair(gripper), parameters.metric_samples, parameters.metric_seed),
      object_(object) {
  if (gripper.soft_finger) geometry::boundary_surface(gripper.soft_finger->mesh, &surface_to_tet_);
}

GraspDistances::GraspDistances(const trial::HandTrialScene& hand,
                               const geometry::SurfaceMesh& object,
                               const trial::TrialParameters& parameters)
    : points_(hand.rest_surface(), parameters.metric_samples, parameters.metric_seed),
      object_(object) {
  // The links with a surface in link order, as HandTrialScene::surface_vertices orders them.
  const std::vector<grippers::KinematicLink>& links = hand.kinematics().links();
  for (std::size_t l = 0; l < links.size(); ++l) {
    if (links[l].surface.triangles.rows() == 0) continue;
    parts_.push_back(links[l].surface.vertices);
    part_links_.push_back(static_cast<int>(l));
  }
}

metrics::DistanceMetrics GraspDistances::operator()(const std::array<Eigen::Isometry3d, 2>& fingers,
                                                    const Eigen::Isometry3d& object) const {
  return at({fingers[0], fingers[1]}, object);
}

metrics::DistanceMetrics GraspDistances::operator()(
    const std::array<geometry::Vertices, 2>& fingers, const Eigen::Isometry3d& object) const {
  if (surface_to_tet_.size() == 0) {
    throw std::invalid_argument("GraspDistances: tet vertices given for rigid fingers");
  }
  geometry::Vertices world(2 * surface_to_tet_.size(), 3);
  for (int j = 0; j < 2; ++j) {
    for (Eigen::Index v = 0; v < surface_to_tet_.size(); ++v) {
      world.row(j * surface_to_tet_.size() + v) = fingers[j].row(surface_to_tet_[v]);
    }
  }
  return measured(world, object);
}

metrics::DistanceMetrics GraspDistances::operator()(const std::vector<Eigen::Isometry3d>& links,
                                                    const Eigen::Isometry3d& object) const {
  std::vector<Eigen::Isometry3d> poses;
  for (const int l : part_links_) poses.push_back(links.at(static_cast<std::size_t>(l)));
  return at(poses, object);
}

metrics::DistanceMetrics GraspDistances::at(const std::vector<Eigen::Isometry3d>& part_poses,
                                            const Eigen::Isometry3d& object) const {
  Eigen::Index rows = 0;
  for (const geometry::Vertices& part : parts_) rows += part.rows();
  geometry::Vertices world(rows, 3);
  Eigen::Index row = 0;
  for (std::size_t p = 0; p < parts_.size(); ++p) {
    for (Eigen::Index v = 0; v < parts_[p].rows(); ++v) {
      world.row(row++) = (part_poses[p] * parts_[p].row(v).transpose()).transpose();
    }
  }
  return measured(world, object);
}

metrics::DistanceMetrics GraspDistances::measured(const geometry::Vertices& world,
                                                  const Eigen::Isometry3d& object) const {
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
