#pragma once
// The surface all contacts are found on: the vertices of every body, their edges and faces, and
// which pairs of bodies may touch, with what friction. Built with the model (Model::build); the
// broad phase and the contact terms know bodies only as this mesh shows them.
#include <array>
#include <vector>

#include "solver/scene/scene.hpp"

namespace grip::solver {

struct CollisionMesh {
  std::vector<int> vertex_body;   // body of each collision vertex
  std::vector<int> vertex_local;  // its index among the body's rest vertices
  // Body b's collision vertices: [body_first_vertex[b], body_first_vertex[b + 1]).
  std::vector<int> body_first_vertex{0};
  // Each collision vertex at rest, in its body's rest frame (BodySubsystem::rest_vertex): rest
  // lengths, and a deforming body's own pairs near at rest.
  Vertices rest;
  std::vector<std::array<int, 2>> edges;  // collision vertex indices
  std::vector<std::array<int, 3>> faces;
  // A deforming body's own point-triangle and edge-edge pairs that lie within d_hat of each
  // other at rest (fine surface triangles at a rim, say), as find_contact_candidates lists them,
  // sorted. No barrier acts on them: it would push the surface apart at rest, against its own
  // elasticity, from the first step. CCD still keeps them from crossing.
  std::vector<std::array<int, 4>> point_triangle_near_at_rest;
  std::vector<std::array<int, 4>> edge_edge_near_at_rest;
  // mu of each ordered pair of bodies (body_a * body_count() + body_b), or a negative value when
  // the two never touch (both without DOFs, a body that keeps its shape with itself, a pinned
  // body and its mount, two bodies of one collision group).
  std::vector<double> friction;
  // Per body: whether it is one of a set of bodies that never touch each other (the bodies
  // without DOFs, with the bodies of collision groups when no pair of the set may touch: a
  // hand's driven links and its palm). The broad phase looks for their contacts only among the
  // others' primitives.
  std::vector<char> untouching;

  int size() const { return static_cast<int>(vertex_body.size()); }
  int body_count() const { return static_cast<int>(body_first_vertex.size()) - 1; }
  double pair_friction(int body_a, int body_b) const {
    return friction[static_cast<std::size_t>(body_a) * static_cast<std::size_t>(body_count()) +
                    static_cast<std::size_t>(body_b)];
  }
  bool may_touch(int body_a, int body_b) const { return pair_friction(body_a, body_b) >= 0.0; }
  bool among_untouching(int body) const { return untouching[static_cast<std::size_t>(body)]; }
  bool near_at_rest(bool edge_edge, const std::array<int, 4>& pair) const;
  Eigen::Vector3d rest_position(int v) const { return rest.row(v).transpose(); }
};

}  // namespace grip::solver
