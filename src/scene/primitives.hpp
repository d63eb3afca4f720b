#pragma once
// Bodies for scenes built in code or read from scene files: a surface made a body, a tet mesh
// made an FEM body's mesh, and a box as a structured tet grid (exact volume, no meshing needed).
// Surface shapes come from src/geometry/primitives.hpp.
#include <string>

#include "solver/scene/scene.hpp"
#include "src/geometry/mesh.hpp"

namespace grip::scene {

// A body of the given type whose collision mesh is `mesh` (in its frame), its frame starting
// at `position`.
solver::BodyDescription surface_body(const std::string& name, solver::BodyType type,
                                     const geometry::SurfaceMesh& mesh,
                                     const Eigen::Vector3d& position);

// Gives an FEM body a tet mesh: its vertices, its tets and its boundary triangles (indexing
// the tet mesh's vertices, as the solver wants them).
void set_fem_mesh(solver::BodyDescription& body, const geometry::TetMesh& tets);

// A box of full extents `size` split into cells of about `cell` (at least one per axis), six
// positively oriented tets per cell (Kuhn's split, conforming across cells).
geometry::TetMesh box_tets(const Eigen::Vector3d& size, double cell);

// How many tets box_tets(size, cell) makes, counted in floating point so that a fine cell gives
// a large number rather than an overflow: check it before building.
double box_tet_count(const Eigen::Vector3d& size, double cell);

}  // namespace grip::scene
