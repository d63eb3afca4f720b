#pragma once
// An object surface prepared once for synthesis: its triangle tree (closest points, exact mesh
// distances) and exact signed distance, and the clearance test every emitted candidate passes.
#include <memory>

#include <Eigen/Core>

#include "src/geometry/mesh.hpp"
#include "src/geometry/signed_distance.hpp"
#include "src/synth/triangle_tree.hpp"

namespace grip::synth {

class PreparedObject {
 public:
  // `closed_surface` must be closed and outward (geometry::repair_surface makes it so).
  explicit PreparedObject(geometry::SurfaceMesh closed_surface);

  const geometry::SurfaceMesh& surface() const { return surface_; }
  const TriangleTree& tree() const { return tree_; }
  const geometry::SignedDistance& signed_distance() const { return *signed_distance_; }
  Eigen::Vector3d centroid() const { return centroid_; }  // area-weighted surface centroid

  // Exact clearance (m) between a gripper surface (closed components, any number) and the
  // object: the smallest triangle-triangle distance, capped at `cutoff`; 0 when they
  // intersect, when a gripper component lies inside the object or when the object could lie
  // inside a gripper component (its bounding box fits in the component's). Thread-safe.
  double clearance(const geometry::SurfaceMesh& gripper, double cutoff) const;

 private:
  geometry::SurfaceMesh surface_;
  TriangleTree tree_;
  std::shared_ptr<geometry::SignedDistance> signed_distance_;
  Eigen::Vector3d centroid_;
  Eigen::Vector3d lower_;
  Eigen::Vector3d upper_;
};

}  // namespace grip::synth
