#include "solver/contact/collision_mesh.hpp"

#include <algorithm>

namespace grip::solver {

bool CollisionMesh::near_at_rest(bool edge_edge, const std::array<int, 4>& pair) const {
  const auto& pairs = edge_edge ? edge_edge_near_at_rest : point_triangle_near_at_rest;
  return std::binary_search(pairs.begin(), pairs.end(), pair);
}

}  // namespace grip::solver
