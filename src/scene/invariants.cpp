#include "src/scene/invariants.hpp"

#include "src/geometry/intersections.hpp"

namespace grip::scene {

int count_intersections(const solver::Environment& environment) {
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

}  // namespace grip::scene
