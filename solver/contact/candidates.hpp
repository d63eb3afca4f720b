#pragma once
// The broad phase of one environment: point-triangle and edge-edge pairs of the collision mesh
// whose boxes, swept from one configuration to another and inflated by d_hat, overlap. The
// list holds every pair that can come within d_hat anywhere on the straight path between the
// two configurations, so it serves CCD and every barrier evaluation along that path.
#include <array>
#include <utility>
#include <vector>

#include "solver/contact/primitive_trees.hpp"
#include "solver/model.hpp"

namespace grip::solver {

// A broad-phase candidate: two primitives that may come within d_hat.
struct ContactCandidate {
  bool edge_edge = false;      // else point-triangle
  std::array<int, 4> vertex;   // collision vertices: (p, t0, t1, t2) or (ea0, ea1, eb0, eb1)
  double friction = 0.0;       // mu of the two bodies
  double mollifier_eps = 0.0;  // edge-edge: eps_x of the parallel-edge mollifier (rest lengths)
  // One FEM body's primitives within d_hat at rest (CollisionMesh::point_triangle_near_at_rest):
  // CCD watches the pair, no barrier acts on it.
  bool near_at_rest = false;
};

// Pairs near the path start -> end (both collision vertex positions, one row per vertex), in a
// deterministic order. Pairs that share a vertex, and pairs of bodies that never touch, are left
// out.
std::vector<ContactCandidate> find_contact_candidates(const Model& model, const Vertices& start,
                                                      const Vertices& end, double d_hat);

// The broad phase kept from call to call (one per environment), so that its trees keep their
// storage and shape; it finds exactly what find_contact_candidates finds.
class ContactBroadPhase {
 public:
  std::vector<ContactCandidate> find(const Model& model, const Vertices& start, const Vertices& end,
                                     double d_hat);

 private:
  PrimitiveTrees faces_;
  PrimitiveTrees edges_;
  // Scratch of one call.
  std::vector<Aabb> vertex_boxes_;
  std::vector<Aabb> body_boxes_;
  std::vector<char> reaches_;
  std::vector<Aabb> boxes_;
  std::vector<int> first_vertex_;
};

// The FEM bodies' own pairs within d_hat at rest, point-triangle then edge-edge, each sorted:
// what Model keeps in CollisionMesh.
std::pair<std::vector<std::array<int, 4>>, std::vector<std::array<int, 4>>> self_pairs_near_at_rest(
    const Model& model);

}  // namespace grip::solver
