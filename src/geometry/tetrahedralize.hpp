#pragma once
// Tetrahedralization of a closed surface with CGAL Mesh_3 (polyhedral domain with sharp
// features protected), to a target edge length with quality bounds.
#include <cmath>
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
  // Sliver perturbation and exudation lift every dihedral angle above this where they can;
  // both run until they cannot improve any more (no time limit), so the mesh is the same on
  // every machine.
  double sliver_bound_deg = 12.0;
  // Protecting balls on sharp features shrink where two features come close, but not below
  // this fraction of edge_length; features closer than that are not kept apart.
  double minimal_ball_ratio = 0.05;
  // Where the surface seeding of a smooth shape (one without sharp features) starts: a
  // different seed gives a different but equally valid mesh; the same seed, the same mesh.
  std::uint32_t seed = 0;
  // A graded mesh: below a depth of edge_length, a cell's circumradius may grow with its
  // circumcentre's depth, by interior_growth per metre (0: edge_length throughout, the
  // default here), up to interior_size_ratio times edge_length. The tets with a vertex on the
  // surface keep the uniform mesh's bound (forced below a growth of 1, measured at 1: see
  // tetrahedralize.cpp), so contacts see the same tets; the inside, which a grasp strains
  // least, gets fewer and larger ones.
  double interior_growth = 0.0;
  double interior_size_ratio = 3.0;
};

// Soft objects' interior growth in `grip trial --soft`, a job's soft [[objects]] and the
// benchmarks' production models: on the LEAP hand's box 2.4 times fewer tets and 4.8 times
// less CPU than a uniform mesh, with the same verdicts (docs/results.md, "Graded soft meshes").
inline constexpr double kSoftObjectInteriorGrowth = 1.0;
// The largest interior growth the command line and a job accept.
inline constexpr double kMaxInteriorGrowth = 4.0;

// The most tets grip builds a mesh of (`grip asset prepare --edge`, a scene's FEM `resolution`,
// `grip trial --soft --tet-edge`), checked on an estimate before meshing: more would take hours
// to mesh and to simulate.
inline constexpr double kMaxEstimatedTets = 5e6;

// About how many tets of edge `edge_length` fill `volume`: a regular tet of edge h has volume
// h^3 / (6 sqrt 2).
inline double estimated_tet_count(double volume, double edge_length) {
  return volume / (std::pow(edge_length, 3) / (6.0 * std::sqrt(2.0)));
}

// Tetrahedralizes the volume bounded by `closed_surface`, which must be closed, manifold and
// free of self-intersections (repair_surface in repair.hpp makes it so). The tets are
// positively oriented. Throws std::invalid_argument naming what is wrong with the input;
// `source` names it in that message (a file name, an object category).
TetMesh tetrahedralize(const SurfaceMesh& closed_surface, const TetOptions& options,
                       const std::string& source = "surface");

}  // namespace grip::geometry
