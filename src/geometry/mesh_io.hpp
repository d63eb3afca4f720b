#pragma once
// Reading surface meshes (OBJ, STL, PLY, OFF) and writing surface (OBJ) and tetrahedral
// (Gmsh 2.2 .msh, VTK .vtu) meshes. Every failure throws std::runtime_error naming the file.
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "src/geometry/mesh.hpp"

namespace grip::geometry {

// Reads a polygon surface; the format follows the extension (.obj, .stl, .ply, .off, any
// case). Exact duplicate points are merged (STL stores each corner of each triangle) and
// polygons with more than three corners are split into a fan of triangles (exact for convex
// polygons). No other repair happens here: see repair.hpp. Throws if the file cannot be read
// or holds no triangle.
SurfaceMesh read_surface_mesh(const std::filesystem::path& file);

void write_obj(const std::filesystem::path& file, const SurfaceMesh& mesh);

// Gmsh 2.2 ASCII; every tet is element type 4 with physical and elementary tag 1.
void write_msh(const std::filesystem::path& file, const TetMesh& mesh);

// One scalar value per tet, written as VTK cell data under `name`.
struct CellField {
  std::string name;
  Eigen::VectorXd values;
};

// VTK XML unstructured grid (ASCII), cells of type VTK_TETRA. Throws if a field's size is
// not the number of tets.
void write_vtu(const std::filesystem::path& file, const TetMesh& mesh,
               const std::vector<CellField>& cell_fields = {});

}  // namespace grip::geometry
