#include "src/scene/invariants.hpp"

#include <memory>
#include <stdexcept>
#include <vector>

#include "src/geometry/intersections.hpp"
#include "src/geometry/signed_distance.hpp"

namespace grip::scene {

int count_intersections(const solver::EnvironmentHandle& environment) {
  const solver::Model& model = environment.model();
  const solver::CollisionMesh& mesh = model.collision();
  geometry::Triangles faces(static_cast<Eigen::Index>(mesh.faces.size()), 3);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    faces.row(static_cast<Eigen::Index>(f)) << mesh.faces[f][0], mesh.faces[f][1], mesh.faces[f][2];
  }
  geometry::Edges edges(static_cast<Eigen::Index>(mesh.edges.size()), 2);
  for (std::size_t e = 0; e < mesh.edges.size(); ++e) {
    edges.row(static_cast<Eigen::Index>(e)) << mesh.edges[e][0], mesh.edges[e][1];
  }
  return geometry::count_intersections(environment.collision_positions(), faces, edges,
                                       mesh.vertex_body,
                                       [&](int a, int b) { return model.may_touch(a, b); });
}

std::optional<std::pair<int, int>> find_contained_body(
    const solver::EnvironmentHandle& environment) {
  const solver::Model& model = environment.model();
  const solver::CollisionMesh& mesh = model.collision();
  const geometry::Vertices positions = environment.collision_positions();
  const int bodies = static_cast<int>(model.bodies().size());
  // Each body's collision vertices and surface, indexed locally.
  std::vector<std::vector<int>> vertices(bodies);
  std::vector<int> local(mesh.vertex_body.size());
  for (int v = 0; v < mesh.size(); ++v) {
    std::vector<int>& own = vertices[mesh.vertex_body[v]];
    local[v] = static_cast<int>(own.size());
    own.push_back(v);
  }
  std::vector<std::vector<std::array<int, 3>>> faces(bodies);
  for (const std::array<int, 3>& f : mesh.faces) {
    faces[mesh.vertex_body[f[0]]].push_back({local[f[0]], local[f[1]], local[f[2]]});
  }
  std::vector<geometry::Vertices> points(bodies);
  std::vector<std::unique_ptr<geometry::SignedDistance>> inside(bodies);
  for (int b = 0; b < bodies; ++b) {
    points[b].resize(static_cast<Eigen::Index>(vertices[b].size()), 3);
    for (std::size_t k = 0; k < vertices[b].size(); ++k) {
      points[b].row(static_cast<Eigen::Index>(k)) = positions.row(vertices[b][k]);
    }
    if (faces[b].empty()) continue;
    geometry::SurfaceMesh surface;
    surface.vertices = points[b];
    surface.triangles.resize(static_cast<Eigen::Index>(faces[b].size()), 3);
    for (std::size_t f = 0; f < faces[b].size(); ++f) {
      surface.triangles.row(static_cast<Eigen::Index>(f)) << faces[b][f][0], faces[b][f][1],
          faces[b][f][2];
    }
    try {
      inside[b] = std::make_unique<geometry::SignedDistance>(surface);
    } catch (const std::invalid_argument&) {
      // An open surface has no inside to contain anything.
    }
  }
  for (int a = 0; a < bodies; ++a) {
    for (int b = 0; b < bodies; ++b) {
      if (a == b || !inside[b] || points[a].rows() == 0 || !model.may_touch(a, b)) continue;
      const Eigen::Matrix<double, 2, 3> box = inside[b]->bounds();
      const bool in_box = ((points[a].rowwise() - box.row(0)).array() >= 0).all() &&
                          ((points[a].rowwise() - box.row(1)).array() <= 0).all();
      if (in_box && ((*inside[b]).evaluate(points[a]).array() > 0).all()) return {{a, b}};
    }
  }
  return std::nullopt;
}

}  // namespace grip::scene
