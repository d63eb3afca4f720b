#pragma once
// Reading tetrahedral meshes made by other tools, for a soft body the user brings (a gripper's
// finger): legacy VTK unstructured grids (.vtk, ASCII, file versions up to 4.2 and 5.1), Gmsh
// (.msh, ASCII, formats 2.2 and 4.1) and MEDIT (.mesh, ASCII). Only the 4-node tets are read;
// other cells (surface triangles, lines, points) are skipped, and vertices no tet uses are
// dropped. Every failure throws std::runtime_error naming the file and what to do.
#include <filesystem>
#include <string>

#include "src/geometry/mesh.hpp"

namespace grip::geometry {

// True for the extensions read_tet_mesh reads (.vtk, .msh, .mesh; any case).
bool is_tet_mesh_file(const std::filesystem::path& file);

// The tets of `file`, the format following its extension (any case), vertices in file order
// (those no tet uses dropped), indices zero-based, orientation as the file gives it: see
// check_soft_body_mesh for what makes a mesh simulable.
TetMesh read_tet_mesh(const std::filesystem::path& file);

// Checks a soft body's rest mesh and orients it: tets all negatively oriented (a convention of
// some tools) are flipped; a mix of orientations (inverted tets), a tet of near-zero volume
// (degenerate), a boundary that is not a closed manifold, or a body larger than `max_size_m`
// across (millimetres read as metres) throws std::runtime_error naming `source` and the fix.
void check_soft_body_mesh(TetMesh& mesh, const std::string& source, double max_size_m = 2.0);

}  // namespace grip::geometry
