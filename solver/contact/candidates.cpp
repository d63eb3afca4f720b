#include "solver/contact/candidates.hpp"

#include "solver/contact/bvh.hpp"
#include "solver/kernels/edge_edge_mollifier.hpp"

namespace grip::solver {
namespace {

Aabb swept_box(const Vertices& start, const Vertices& end, std::initializer_list<int> vertices,
               double margin) {
  Aabb box;
  for (int v : vertices) {
    box.expand(Eigen::Vector3d(start.row(v)));
    box.expand(Eigen::Vector3d(end.row(v)));
  }
  box.inflate(margin);
  return box;
}

Eigen::Vector3d rest_position(const Model& model, int collision_vertex) {
  const CollisionMesh& mesh = model.collision();
  return model.bodies()[mesh.vertex_body[collision_vertex]].rest.row(
      mesh.vertex_local[collision_vertex]);
}

}  // namespace

std::vector<ContactCandidate> find_contact_candidates(const Model& model, const Vertices& start,
                                            const Vertices& end, double d_hat) {
  const CollisionMesh& mesh = model.collision();
  // Two boxes each inflated by half of d_hat overlap whenever their contents come within d_hat.
  const double margin = 0.5 * d_hat * (1.0 + 1e-9);

  std::vector<Aabb> face_boxes(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& t = mesh.faces[f];
    face_boxes[f] = swept_box(start, end, {t[0], t[1], t[2]}, margin);
  }
  std::vector<Aabb> edge_boxes(mesh.edges.size());
  for (std::size_t e = 0; e < mesh.edges.size(); ++e) {
    edge_boxes[e] = swept_box(start, end, {mesh.edges[e][0], mesh.edges[e][1]}, margin);
  }
  Bvh faces;
  faces.build(face_boxes);
  Bvh edges;
  edges.build(edge_boxes);

  // Kinematic bodies never touch each other (a hand's links, a gripper's jaws), and they can
  // hold most of the primitives: theirs look only among the other bodies' primitives, in a
  // second, smaller tree over those.
  auto kinematic = [&](int vertex) {
    return model.bodies()[mesh.vertex_body[vertex]].type == BodyType::kKinematic;
  };
  std::vector<int> free_faces, free_edges;  // indices into mesh.faces, mesh.edges
  std::vector<Aabb> free_face_boxes, free_edge_boxes;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    if (kinematic(mesh.faces[f][0])) continue;
    free_faces.push_back(static_cast<int>(f));
    free_face_boxes.push_back(face_boxes[f]);
  }
  for (std::size_t e = 0; e < mesh.edges.size(); ++e) {
    if (kinematic(mesh.edges[e][0])) continue;
    free_edges.push_back(static_cast<int>(e));
    free_edge_boxes.push_back(edge_boxes[e]);
  }
  Bvh free_face_tree;
  free_face_tree.build(free_face_boxes);
  Bvh free_edge_tree;
  free_edge_tree.build(free_edge_boxes);
  // Calls visit(face or edge index) for each box of the right tree that overlaps `box`.
  auto query = [](const Bvh& all, const Bvh& free, const std::vector<int>& free_index,
                  bool from_kinematic, const Aabb& box, auto&& visit) {
    if (from_kinematic) {
      free.query(box, [&](int k) { visit(free_index[static_cast<std::size_t>(k)]); });
    } else {
      all.query(box, visit);
    }
  };

  std::vector<ContactCandidate> pairs;
  for (int v = 0; v < mesh.size(); ++v) {
    const int body_v = mesh.vertex_body[v];
    query(faces, free_face_tree, free_faces, kinematic(v), swept_box(start, end, {v}, margin),
          [&](int f) {
            const auto& t = mesh.faces[f];
            if (t[0] == v || t[1] == v || t[2] == v) return;
            const double mu = model.pair_friction(body_v, mesh.vertex_body[t[0]]);
            if (mu < 0) return;
            pairs.push_back({false, {v, t[0], t[1], t[2]}, mu, 0.0});
          });
  }
  for (int a = 0; a < static_cast<int>(mesh.edges.size()); ++a) {
    const auto& ea = mesh.edges[a];
    const int body_a = mesh.vertex_body[ea[0]];
    // Each unordered pair once: found from its lower index when both trees hold the other
    // edge, from the kinematic edge's side otherwise (only it looks in the smaller tree).
    query(edges, free_edge_tree, free_edges, kinematic(ea[0]), edge_boxes[a], [&](int b) {
      if (b == a) return;
      if (kinematic(ea[0]) == kinematic(mesh.edges[b][0]) ? b < a : kinematic(mesh.edges[b][0])) {
        return;
      }
      const auto& eb = mesh.edges[b];
      if (ea[0] == eb[0] || ea[0] == eb[1] || ea[1] == eb[0] || ea[1] == eb[1]) return;
      const double mu = model.pair_friction(body_a, mesh.vertex_body[eb[0]]);
      if (mu < 0) return;
      // The threshold depends on rest lengths only, so each edge may be in its own body frame.
      const double eps = kernels::edge_edge_mollifier_threshold(
          rest_position(model, ea[0]), rest_position(model, ea[1]), rest_position(model, eb[0]),
          rest_position(model, eb[1]));
      pairs.push_back({true, {ea[0], ea[1], eb[0], eb[1]}, mu, eps});
    });
  }
  return pairs;
}

}  // namespace grip::solver
