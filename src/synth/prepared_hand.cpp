#include "src/synth/prepared_hand.hpp"

#include <algorithm>
#include <set>

namespace grip::synth {

PreparedHand::PreparedHand(grippers::HandModel model) : model_(std::move(model)) {
  const grippers::KinematicTree& tree = model_.kinematics;
  for (const grippers::ContactCandidate& c : model_.points.contacts) {
    contacts_.push_back({tree.link_index(c.link), c.position, c.normal.normalized(), 0.0});
  }
  for (const grippers::PenetrationSphere& k : model_.points.keypoints) {
    keypoints_.push_back({tree.link_index(k.link), k.center, Eigen::Vector3d::Zero(), k.radius});
  }
  for (std::size_t a = 0; a < keypoints_.size(); ++a) {
    for (std::size_t b = a + 1; b < keypoints_.size(); ++b) {
      const int la = keypoints_[a].link, lb = keypoints_[b].link;
      if (la != lb && !adjacent(la, lb)) {
        keypoint_pairs_.emplace_back(static_cast<int>(a), static_cast<int>(b));
      }
    }
  }
  std::set<std::pair<int, int>> edges;
  int offset = 0;
  std::vector<Eigen::Vector3i> faces;
  for (int l = 0; l < link_count(); ++l) {
    const geometry::SurfaceMesh& surface = tree.links()[static_cast<std::size_t>(l)].surface;
    if (surface.triangles.rows() == 0) {
      link_distances_.push_back(nullptr);
      link_boxes_.push_back(Eigen::Matrix<double, 2, 3>::Zero());
      continue;
    }
    link_distances_.push_back(std::make_shared<geometry::SignedDistance>(surface));
    Eigen::Matrix<double, 2, 3> box;
    box.row(0) = surface.vertices.colwise().minCoeff();
    box.row(1) = surface.vertices.colwise().maxCoeff();
    link_boxes_.push_back(box);
    for (int f = 0; f < surface.triangles.rows(); ++f) {
      const Eigen::Vector3i t = surface.triangles.row(f).transpose().array() + offset;
      faces.push_back(t);
      for (int k = 0; k < 3; ++k) {
        const int a = t(k), b = t((k + 1) % 3);
        edges.emplace(std::min(a, b), std::max(a, b));
      }
    }
    for (int v = 0; v < surface.vertices.rows(); ++v) vertex_link_.push_back(l);
    offset += static_cast<int>(surface.vertices.rows());
  }
  merged_faces_.resize(static_cast<int>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    merged_faces_.row(static_cast<int>(f)) = faces[f].transpose();
  merged_edges_.resize(static_cast<int>(edges.size()), 2);
  int e = 0;
  for (const auto& [a, b] : edges) merged_edges_.row(e++) << a, b;
}

bool PreparedHand::adjacent(int a, int b) const {
  const auto& joints = model_.kinematics.joints();
  const auto& links = model_.kinematics.links();
  const auto parent_of = [&](int link) {
    const int j = links[static_cast<std::size_t>(link)].parent_joint;
    return j < 0 ? -1 : joints[static_cast<std::size_t>(j)].parent_link;
  };
  return parent_of(a) == b || parent_of(b) == a;
}

geometry::SurfaceMesh PreparedHand::posed_link(const std::vector<Eigen::Isometry3d>& poses,
                                               int link) const {
  geometry::SurfaceMesh mesh = model_.kinematics.links()[static_cast<std::size_t>(link)].surface;
  const Eigen::Isometry3d& pose = poses[static_cast<std::size_t>(link)];
  for (int v = 0; v < mesh.vertices.rows(); ++v) {
    mesh.vertices.row(v) = (pose * Eigen::Vector3d(mesh.vertices.row(v))).transpose();
  }
  return mesh;
}

int PreparedHand::self_intersections(const std::vector<Eigen::Isometry3d>& poses) const {
  geometry::Vertices positions(static_cast<int>(vertex_link_.size()), 3);
  int row = 0;
  for (int l = 0; l < link_count(); ++l) {
    const geometry::SurfaceMesh& surface =
        model_.kinematics.links()[static_cast<std::size_t>(l)].surface;
    if (surface.triangles.rows() == 0) continue;
    for (int v = 0; v < surface.vertices.rows(); ++v) {
      positions.row(row++) =
          (poses[static_cast<std::size_t>(l)] * Eigen::Vector3d(surface.vertices.row(v)))
              .transpose();
    }
  }
  return geometry::count_intersections(positions, merged_faces_, merged_edges_, vertex_link_,
                                       [this](int a, int b) { return a != b && !adjacent(a, b); });
}

}  // namespace grip::synth
