// A settled grasp's contact patch (the collision vertices of one side that bore a contact
// force) and the rigid motion that best carries it to where its vertices are now.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "solver/scene/scene.hpp"

namespace grip::trial {

// x -> rotation x + translation.
struct RigidMotion {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  Eigen::Vector3d operator()(const Eigen::Vector3d& x) const { return rotation * x + translation; }
};

class ContactPatch {
 public:
  // A vertex of the patch, where it was when the grasp settled and its weight (the magnitude of
  // its contact force then).
  void add(int vertex, const Eigen::Vector3d& settled, double weight);
  bool empty() const { return vertices_.empty(); }
  int size() const { return static_cast<int>(vertices_.size()); }

  // The weighted least-squares rigid motion from the settled patch to its vertices' rows of x
  // (Kabsch). A patch that does not spread in two directions (one point, or points on a line)
  // does not determine a turn about that line: it gives its weighted mean's translation alone.
  RigidMotion motion(const solver::Vertices& x) const;

 private:
  struct Vertex {
    int index = 0;
    Eigen::Vector3d settled = Eigen::Vector3d::Zero();
    double weight = 0.0;
  };
  std::vector<Vertex> vertices_;
};

}  // namespace grip::trial
