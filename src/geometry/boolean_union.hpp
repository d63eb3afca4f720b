#pragma once
// Union of two closed solids by exact corefinement (CGAL), for composite objects such as a
// mug body and its handle.
#include <string>

#include "src/geometry/mesh.hpp"

namespace grip::geometry {

// Both inputs must be closed, outward oriented and free of self-intersections. Throws
// std::invalid_argument naming `what` if they are not or the union cannot be computed.
SurfaceMesh boolean_union(const SurfaceMesh& a, const SurfaceMesh& b,
                          const std::string& what = "union");

}  // namespace grip::geometry
