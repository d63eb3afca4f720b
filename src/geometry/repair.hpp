#pragma once
// Repair of an input surface into a closed, manifold, outward-oriented, self-intersection-free
// surface that bounds a volume, with a report of what was changed.
#include <string>

#include "src/geometry/mesh.hpp"

namespace grip::geometry {

struct RepairOptions {
  // Alpha wrapping, the fallback for surfaces that stay open or self-intersecting, wraps the
  // input with a ball of radius alpha and offsets the result by `offset`; both are given as
  // fractions of the input's bounding-box diagonal. A smaller alpha follows the input more
  // closely (and yields more triangles); holes narrower than about alpha get closed over.
  double alpha_ratio = 1.0 / 100.0;
  double offset_ratio = 1.0 / 3000.0;
  bool fill_holes = true;        // close remaining border loops by triangulating them
  bool allow_alpha_wrap = true;  // false: fail instead of wrapping
};

// What repair_surface changed, in counts.
struct RepairReport {
  int points_removed = 0;          // duplicate and unused points
  int faces_removed = 0;           // degenerate and duplicate faces
  int points_split = 0;            // copies made to resolve non-manifold vertices
  int faces_reoriented = 0;        // faces whose winding was flipped
  int edges_stitched = 0;          // border edge pairs glued together
  int holes_filled = 0;            // border loops closed by triangulation
  bool self_intersecting = false;  // whether the surface intersected itself before wrapping
  bool alpha_wrapped = false;      // whether the alpha-wrap fallback produced the result
  double input_volume = 0.0;       // signed volume of the input soup (m^3), indicative only
  double volume = 0.0;             // volume of the repaired surface (m^3)

  // One line for people: "merged 3 duplicate points, stitched 12 edges, ...".
  std::string summary() const;
};

struct RepairedSurface {
  SurfaceMesh mesh;
  RepairReport report;
};

// Throws std::invalid_argument naming `source` when the input is empty, flat (all points in
// one plane: zero volume), or cannot be repaired with the given options.
RepairedSurface repair_surface(const SurfaceMesh& input, const RepairOptions& options = {},
                               const std::string& source = "surface");

}  // namespace grip::geometry
