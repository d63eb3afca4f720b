#pragma once
// Plain triangle and tetrahedral meshes shared by geometry, objects, grippers and the solver's
// scene set-up: vertex positions in metres, one row per vertex, zero-based indices.
#include <Eigen/Core>

namespace grip::geometry {

using Vertices = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using Triangles = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;
using Tetrahedra = Eigen::Matrix<int, Eigen::Dynamic, 4, Eigen::RowMajor>;

// A closed surface has outward-facing triangles (counter-clockwise seen from outside).
struct SurfaceMesh {
  Vertices vertices;
  Triangles triangles;
};

// Tets are positively oriented: (v1-v0) x (v2-v0) . (v3-v0) > 0.
struct TetMesh {
  Vertices vertices;
  Tetrahedra tets;
};

}  // namespace grip::geometry
