#pragma once
// Plain measures of a surface mesh: enclosed volume, area, bounding box, and the check that
// a mesh is plausibly in metres.
#include <string>

#include "src/geometry/mesh.hpp"

namespace grip::geometry {

// Signed volume enclosed by a closed surface (divergence theorem); positive when the
// triangles face outward.
double surface_volume(const SurfaceMesh& mesh);

double surface_area(const SurfaceMesh& mesh);

// Length of the axis-aligned bounding box diagonal; 0 for an empty mesh.
double bounding_box_diagonal(const Vertices& vertices);

// Objects grip handles measure between 1 mm and 10 m across. Returns an empty string when the
// bounding-box diagonal lies in that range, otherwise a warning naming `source` and the
// likely unit mistake (millimetres, or a model 1000x too small).
std::string metric_scale_warning(const Vertices& vertices, const std::string& source);

}  // namespace grip::geometry
