#pragma once
// The boundary of a tet mesh as a surface mesh: the faces that belong to one tet only.
#include "src/geometry/mesh.hpp"

namespace grip::geometry {

// Faces are oriented outward (counter-clockwise seen from outside) for positively oriented
// tets. The surface keeps only the vertices it uses, renumbered in increasing order of their
// tet-mesh index; `surface_to_tet_vertex`, when given, receives that map.
SurfaceMesh boundary_surface(const TetMesh& mesh, Eigen::VectorXi* surface_to_tet_vertex = nullptr);

}  // namespace grip::geometry
