#pragma once
// Tetrahedralization of a closed surface with CGAL Mesh_3 (polyhedral domain with sharp
// features protected), to a target edge length with quality bounds.
#include <cstdint>
#include <string>

#include "src/geometry/boundary_surface.hpp"
#include "src/geometry/mesh.hpp"
#include "src/geometry/tet_quality.hpp"

namespace grip::geometry {

struct TetOptions {
  double edge_length = 0.01;            // target edge length (m): edge, facet and cell size
  double facet_angle_deg = 25.0;        // lower bound on surface triangle angles
  double facet_distance_ratio = 0.1;    // surface approximation error, times edge_length
  double cell_radius_edge_ratio = 3.0;  // upper bound on circumradius / shortest edge
  double feature_angle_deg = 60.0;      // surface creases sharper than this are kept sharp
  double sliver_bound_deg = 10.0;       // perturbation and exudation aim above this dihedral
  // Sliver perturbation lifts the worst dihedral angles (exudation alone leaves 2-5 degree
  // tets next to the surface) but has no iteration cap and on some inputs runs for tens of
  // seconds, so it stops after this many seconds. It is deterministic unless it hits the cap;
  // then the mesh can depend on the machine's speed and a warning is logged. 0 disables it.
  double perturb_time_limit_s = 10.0;
  std::uint32_t seed = 0;               // Mesh_3's random generator: same seed, same mesh
};

// Tetrahedralizes the volume bounded by `closed_surface`, which must be closed, manifold and
// free of self-intersections (repair_surface in repair.hpp makes it so). The tets are
// positively oriented. Throws std::invalid_argument naming what is wrong with the input;
// `source` names it in that message (a file name, an object category).
TetMesh tetrahedralize(const SurfaceMesh& closed_surface, const TetOptions& options,
                       const std::string& source = "surface");

}  // namespace grip::geometry
