#pragma once
// Exact proximity queries against one triangle mesh (an AABB tree over its triangles): the
// closest point and face to a point, and the smallest distance to another triangle mesh.
#include <memory>

#include <Eigen/Core>

#include "src/geometry/mesh.hpp"

namespace grip::synth {

class TriangleTree {
 public:
  struct Closest {
    Eigen::Vector3d point;  // nearest point on the mesh
    int face = -1;          // its triangle
    double distance = 0.0;  // unsigned, m
  };

  // Triangle-triangle proximity of another mesh to this one.
  struct Proximity {
    double distance = 0.0;      // m; exact when below the cutoff, else the cutoff
    bool intersecting = false;  // some pair of triangles intersects (distance is then 0)
    int face_here = -1;         // the triangles realising `distance` (-1 when at the cutoff)
    int face_other = -1;
  };

  // The mesh is copied. Throws std::invalid_argument for a mesh without triangles.
  explicit TriangleTree(const geometry::SurfaceMesh& mesh);
  ~TriangleTree();
  TriangleTree(TriangleTree&&) noexcept;
  TriangleTree& operator=(TriangleTree&&) noexcept;
  TriangleTree(const TriangleTree&) = delete;
  TriangleTree& operator=(const TriangleTree&) = delete;

  // Thread-safe.
  Closest closest(const Eigen::Vector3d& point) const;

  // Unit normal of a triangle (right-handed winding).
  Eigen::Vector3d face_normal(int face) const;

  // Smallest distance between any triangle of `other` and any triangle of this mesh, computed
  // exactly (CGAL triangle-triangle distance and intersection) for the pairs whose bounding
  // boxes, grown by `cutoff`, overlap. Thread-safe.
  Proximity proximity(const geometry::SurfaceMesh& other, double cutoff) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace grip::synth
