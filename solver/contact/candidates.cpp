#include "solver/contact/candidates.hpp"

#include "solver/body/body.hpp"
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

bool on_kinematic_body(const Model& model, int collision_vertex) {
  return is_kinematic(model.bodies()[model.collision().vertex_body[collision_vertex]]);
}

// One kind of primitive (faces or edges) in two trees. Kinematic bodies never touch each other
// (a hand's links, a gripper's jaws), and they can hold most of the primitives: theirs look
// only among the other bodies' primitives, in a second, smaller tree over those.
class PrimitiveTrees {
 public:
  // boxes[i] and first_vertex[i]: primitive i's swept box and one of its collision vertices.
  PrimitiveTrees(const Model& model, std::vector<Aabb> boxes, const std::vector<int>& first_vertex)
      : boxes_(std::move(boxes)) {
    all_.build(boxes_);
    std::vector<Aabb> free_boxes;
    for (std::size_t i = 0; i < boxes_.size(); ++i) {
      if (on_kinematic_body(model, first_vertex[i])) continue;
      free_index_.push_back(static_cast<int>(i));
      free_boxes.push_back(boxes_[i]);
    }
    free_.build(free_boxes);
  }

  const Aabb& box(int i) const { return boxes_[static_cast<std::size_t>(i)]; }

  // Calls visit(primitive index) for each box of the right tree that overlaps `box`.
  template <typename Visit>
  void query(bool from_kinematic, const Aabb& box, Visit&& visit) const {
    if (from_kinematic) {
      free_.query(box, [&](int k) { visit(free_index_[static_cast<std::size_t>(k)]); });
    } else {
      all_.query(box, visit);
    }
  }

 private:
  std::vector<Aabb> boxes_;
  Bvh all_;
  Bvh free_;
  std::vector<int> free_index_;  // the free tree's boxes as primitive indices
};

PrimitiveTrees face_trees(const Model& model, const Vertices& start, const Vertices& end,
                          double margin) {
  const CollisionMesh& mesh = model.collision();
  std::vector<Aabb> boxes(mesh.faces.size());
  std::vector<int> first(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& t = mesh.faces[f];
    boxes[f] = swept_box(start, end, {t[0], t[1], t[2]}, margin);
    first[f] = t[0];
  }
  return PrimitiveTrees(model, std::move(boxes), first);
}

PrimitiveTrees edge_trees(const Model& model, const Vertices& start, const Vertices& end,
                          double margin) {
  const CollisionMesh& mesh = model.collision();
  std::vector<Aabb> boxes(mesh.edges.size());
  std::vector<int> first(mesh.edges.size());
  for (std::size_t e = 0; e < mesh.edges.size(); ++e) {
    boxes[e] = swept_box(start, end, {mesh.edges[e][0], mesh.edges[e][1]}, margin);
    first[e] = mesh.edges[e][0];
  }
  return PrimitiveTrees(model, std::move(boxes), first);
}

void add_point_triangle_candidates(const Model& model, const Vertices& start, const Vertices& end,
                                   double margin, std::vector<ContactCandidate>& candidates) {
  const CollisionMesh& mesh = model.collision();
  const PrimitiveTrees faces = face_trees(model, start, end, margin);
  for (int v = 0; v < mesh.size(); ++v) {
    const int body_v = mesh.vertex_body[v];
    faces.query(on_kinematic_body(model, v), swept_box(start, end, {v}, margin), [&](int f) {
      const auto& t = mesh.faces[f];
      if (t[0] == v || t[1] == v || t[2] == v) return;
      const double mu = model.pair_friction(body_v, mesh.vertex_body[t[0]]);
      if (mu < 0) return;
      candidates.push_back({false, {v, t[0], t[1], t[2]}, mu, 0.0});
    });
  }
}

void add_edge_edge_candidates(const Model& model, const Vertices& start, const Vertices& end,
                              double margin, std::vector<ContactCandidate>& candidates) {
  const CollisionMesh& mesh = model.collision();
  const PrimitiveTrees edges = edge_trees(model, start, end, margin);
  auto kinematic = [&](int edge) { return on_kinematic_body(model, mesh.edges[edge][0]); };
  for (int a = 0; a < static_cast<int>(mesh.edges.size()); ++a) {
    const auto& ea = mesh.edges[a];
    const int body_a = mesh.vertex_body[ea[0]];
    // Each unordered pair once: found from its lower index when both trees hold the other
    // edge, from the kinematic edge's side otherwise (only it looks in the smaller tree).
    edges.query(kinematic(a), edges.box(a), [&](int b) {
      if (b == a) return;
      if (kinematic(a) == kinematic(b) ? b < a : kinematic(b)) return;
      const auto& eb = mesh.edges[b];
      if (ea[0] == eb[0] || ea[0] == eb[1] || ea[1] == eb[0] || ea[1] == eb[1]) return;
      const double mu = model.pair_friction(body_a, mesh.vertex_body[eb[0]]);
      if (mu < 0) return;
      // The threshold depends on rest lengths only, so each edge may be in its own body frame.
      const double eps = kernels::edge_edge_mollifier_threshold(
          rest_position(model, ea[0]), rest_position(model, ea[1]), rest_position(model, eb[0]),
          rest_position(model, eb[1]));
      candidates.push_back({true, {ea[0], ea[1], eb[0], eb[1]}, mu, eps});
    });
  }
}

}  // namespace

std::vector<ContactCandidate> find_contact_candidates(const Model& model, const Vertices& start,
                                                      const Vertices& end, double d_hat) {
  // Two boxes each inflated by half of d_hat overlap whenever their contents come within d_hat.
  const double margin = 0.5 * d_hat * (1.0 + 1e-9);
  std::vector<ContactCandidate> candidates;
  add_point_triangle_candidates(model, start, end, margin, candidates);
  add_edge_edge_candidates(model, start, end, margin, candidates);
  return candidates;
}

}  // namespace grip::solver
