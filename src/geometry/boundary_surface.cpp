#include "src/geometry/boundary_surface.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <vector>

namespace grip::geometry {

SurfaceMesh boundary_surface(const TetMesh& mesh, Eigen::VectorXi* surface_to_tet_vertex) {
  // Faces of tet (v0, v1, v2, v3) seen from outside, counter-clockwise when it is positive.
  constexpr std::array<std::array<int, 3>, 4> kFaces = {
      {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}}};
  // Sorted corner triple -> (count, oriented face); an ordered map keeps the output order
  // independent of hashing.
  std::map<std::array<int, 3>, std::pair<int, std::array<int, 3>>> faces;
  for (Eigen::Index t = 0; t < mesh.tets.rows(); ++t) {
    for (const auto& local : kFaces) {
      const std::array<int, 3> face = {mesh.tets(t, local[0]), mesh.tets(t, local[1]),
                                       mesh.tets(t, local[2])};
      std::array<int, 3> key = face;
      std::sort(key.begin(), key.end());
      auto [it, inserted] = faces.try_emplace(key, 0, face);
      ++it->second.first;
    }
  }
  std::vector<std::array<int, 3>> boundary;
  std::vector<bool> on_boundary(static_cast<std::size_t>(mesh.vertices.rows()), false);
  for (const auto& [key, entry] : faces) {
    if (entry.first != 1) continue;
    boundary.push_back(entry.second);
    for (int v : key) on_boundary[static_cast<std::size_t>(v)] = true;
  }
  std::vector<int> new_index(on_boundary.size(), -1);
  int count = 0;
  for (std::size_t v = 0; v < on_boundary.size(); ++v) {
    if (on_boundary[v]) new_index[v] = count++;
  }
  SurfaceMesh surface;
  surface.vertices.resize(count, 3);
  if (surface_to_tet_vertex) surface_to_tet_vertex->resize(count);
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
    const int index = new_index[static_cast<std::size_t>(v)];
    if (index < 0) continue;
    surface.vertices.row(index) = mesh.vertices.row(v);
    if (surface_to_tet_vertex) (*surface_to_tet_vertex)[index] = static_cast<int>(v);
  }
  surface.triangles.resize(static_cast<Eigen::Index>(boundary.size()), 3);
  for (std::size_t f = 0; f < boundary.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      surface.triangles(static_cast<Eigen::Index>(f), k) =
          new_index[static_cast<std::size_t>(boundary[f][static_cast<std::size_t>(k)])];
    }
  }
  return surface;
}

}  // namespace grip::geometry
