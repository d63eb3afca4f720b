#pragma once
// Test helpers for surface meshes: closedness with consistent orientation, Euler characteristic.
#include <map>
#include <set>
#include <utility>

#include "src/geometry/mesh.hpp"

namespace grip::grippers::testing {

// True when every directed edge appears exactly once and its reverse exactly once: a closed,
// consistently oriented (orientable) surface.
inline bool is_closed_and_oriented(const geometry::SurfaceMesh& mesh) {
  std::map<std::pair<int, int>, int> directed;
  for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) {
    for (int k = 0; k < 3; ++k) {
      ++directed[{mesh.triangles(t, k), mesh.triangles(t, (k + 1) % 3)}];
    }
  }
  for (const auto& [edge, count] : directed) {
    if (count != 1) return false;
    const auto reverse = directed.find({edge.second, edge.first});
    if (reverse == directed.end() || reverse->second != 1) return false;
  }
  return true;
}

// V - E + F over the vertices the triangles use.
inline long euler_characteristic(const geometry::SurfaceMesh& mesh) {
  std::set<int> vertices;
  std::set<std::pair<int, int>> edges;
  for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.triangles(t, k);
      const int b = mesh.triangles(t, (k + 1) % 3);
      vertices.insert(a);
      edges.insert({std::min(a, b), std::max(a, b)});
    }
  }
  return static_cast<long>(vertices.size()) - static_cast<long>(edges.size()) +
         static_cast<long>(mesh.triangles.rows());
}

}  // namespace grip::grippers::testing
