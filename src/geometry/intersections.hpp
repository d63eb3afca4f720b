#pragma once
// An exact test that a simulated scene is intersection-free: no edge of its collision surface
// crosses or touches a triangle it does not share a vertex with, decided with CGAL's exact
// predicates. The solver keeps every distance positive; this checks the outcome independently.
#include <functional>
#include <vector>

#include "src/geometry/mesh.hpp"

namespace grip::geometry {

using Edges = Eigen::Matrix<int, Eigen::Dynamic, 2, Eigen::RowMajor>;

// positions: one row per vertex; faces and edges index them; vertex_body[v] is v's body.
// Pairs of bodies for which may_touch(a, b) is false (and a == b unless it allows it) are not
// checked. Returns the number of intersecting (edge, triangle) pairs.
int count_intersections(const Vertices& positions, const Triangles& faces, const Edges& edges,
                        const std::vector<int>& vertex_body,
                        const std::function<bool(int, int)>& may_touch);

}  // namespace grip::geometry
