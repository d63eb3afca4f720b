#pragma once
// A dexterous hand prepared once for synthesis: its model, an exact signed distance per link
// (link frame) for the penetration energy, contacts and keypoints resolved to link indices,
// which link pairs may touch, and the merged link topology for exact self-intersection tests.
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "src/geometry/intersections.hpp"
#include "src/geometry/signed_distance.hpp"
#include "src/grippers/hand_model.hpp"

namespace grip::synth {

class PreparedHand {
 public:
  struct LinkPoint {
    int link = -1;
    Eigen::Vector3d position;  // link frame
    Eigen::Vector3d normal;    // unit, link frame (contacts only)
    double radius = 0.0;       // keypoints only
  };

  explicit PreparedHand(grippers::HandModel model);

  const grippers::HandModel& model() const { return model_; }
  const grippers::KinematicTree& kinematics() const { return model_.kinematics; }
  int link_count() const { return static_cast<int>(model_.kinematics.links().size()); }
  const std::vector<LinkPoint>& contacts() const { return contacts_; }
  const std::vector<LinkPoint>& keypoints() const { return keypoints_; }
  // Pairs of keypoints on links that may not touch (neither the same nor parent and child).
  const std::vector<std::pair<int, int>>& keypoint_pairs() const { return keypoint_pairs_; }

  // Exact signed distance (positive inside) to a link's surface in its own frame, and the
  // link-frame box around it; null for a link without geometry.
  const geometry::SignedDistance* link_distance(int link) const {
    return link_distances_[static_cast<std::size_t>(link)].get();
  }
  const Eigen::Matrix<double, 2, 3>& link_box(int link) const {
    return link_boxes_[static_cast<std::size_t>(link)];
  }

  // Links are adjacent when one is the other's parent: their joints' clearances are by design.
  bool adjacent(int a, int b) const;

  // The world-frame surface of one link, or of the whole hand, at the given link poses.
  geometry::SurfaceMesh posed_link(const std::vector<Eigen::Isometry3d>& poses, int link) const;

  // Exact count of intersecting (edge, triangle) pairs between links that are neither the same
  // nor adjacent, at the given link poses (geometry::count_intersections).
  int self_intersections(const std::vector<Eigen::Isometry3d>& poses) const;

 private:
  grippers::HandModel model_;
  std::vector<LinkPoint> contacts_;
  std::vector<LinkPoint> keypoints_;
  std::vector<std::pair<int, int>> keypoint_pairs_;
  std::vector<std::shared_ptr<geometry::SignedDistance>> link_distances_;
  std::vector<Eigen::Matrix<double, 2, 3>> link_boxes_;
  geometry::Triangles merged_faces_;
  geometry::Edges merged_edges_;
  std::vector<int> vertex_link_;
};

}  // namespace grip::synth
