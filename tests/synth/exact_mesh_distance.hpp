#pragma once
// An independent exact check of gripper-object clearance for the synthesis tests: the smallest
// vertex-triangle (both ways) and edge-edge distance between two meshes, by brute force over
// the primitive pairs whose boxes come within the cutoff (the solver's distance kernels), plus
// an exact intersection count (CGAL predicates) and an inside test of one vertex per mesh.
#include <algorithm>
#include <cmath>
#include <set>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "solver/kernels/edge_edge_distance.hpp"
#include "solver/kernels/point_triangle_distance.hpp"
#include "src/geometry/intersections.hpp"
#include "src/geometry/mesh.hpp"
#include "src/geometry/signed_distance.hpp"

namespace grip::synth::testing {

struct Box {
  Eigen::Vector3d lower, upper;
  bool near(const Box& o, double gap) const {
    return (lower.array() <= o.upper.array() + gap).all() &&
           (o.lower.array() <= upper.array() + gap).all();
  }
};

inline std::vector<std::pair<int, int>> mesh_edges(const geometry::SurfaceMesh& m) {
  std::set<std::pair<int, int>> edges;
  for (int f = 0; f < m.triangles.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = m.triangles(f, k), b = m.triangles(f, (k + 1) % 3);
      edges.emplace(std::min(a, b), std::max(a, b));
    }
  }
  return {edges.begin(), edges.end()};
}

// Smallest distance between the surfaces of a and b, capped at `cutoff`.
inline double brute_force_distance(const geometry::SurfaceMesh& a, const geometry::SurfaceMesh& b,
                                   double cutoff) {
  namespace k = grip::solver::kernels;
  double best = cutoff * cutoff;
  const auto vertex = [](const geometry::SurfaceMesh& m, int v) -> Eigen::Vector3d {
    return m.vertices.row(v).transpose();
  };
  const auto point_triangles = [&](const geometry::SurfaceMesh& p, const geometry::SurfaceMesh& t) {
    for (int f = 0; f < t.triangles.rows(); ++f) {
      const Eigen::Vector3d t0 = vertex(t, t.triangles(f, 0)), t1 = vertex(t, t.triangles(f, 1)),
                            t2 = vertex(t, t.triangles(f, 2));
      const Box box{t0.cwiseMin(t1).cwiseMin(t2), t0.cwiseMax(t1).cwiseMax(t2)};
      for (int v = 0; v < p.vertices.rows(); ++v) {
        const Eigen::Vector3d x = vertex(p, v);
        if (!box.near(Box{x, x}, cutoff)) continue;
        best = std::min(best, k::point_triangle_distance_sq(x, t0, t1, t2));
      }
    }
  };
  point_triangles(a, b);
  point_triangles(b, a);
  const auto ea = mesh_edges(a), eb = mesh_edges(b);
  for (const auto& [a0, a1] : ea) {
    const Eigen::Vector3d p0 = vertex(a, a0), p1 = vertex(a, a1);
    const Box box{p0.cwiseMin(p1), p0.cwiseMax(p1)};
    for (const auto& [b0, b1] : eb) {
      const Eigen::Vector3d q0 = vertex(b, b0), q1 = vertex(b, b1);
      if (!box.near(Box{q0.cwiseMin(q1), q0.cwiseMax(q1)}, cutoff)) continue;
      best = std::min(best, k::edge_edge_distance_sq(p0, p1, q0, q1));
    }
  }
  return std::sqrt(best);
}

// Exact intersecting (edge, triangle) pairs between two meshes.
inline int mesh_intersections(const geometry::SurfaceMesh& a, const geometry::SurfaceMesh& b) {
  const auto na = static_cast<int>(a.vertices.rows());
  geometry::Vertices positions(na + b.vertices.rows(), 3);
  positions << a.vertices, b.vertices;
  geometry::Triangles faces(a.triangles.rows() + b.triangles.rows(), 3);
  faces << a.triangles, (b.triangles.array() + na).matrix();
  std::vector<std::pair<int, int>> edges = mesh_edges(a);
  for (const auto& [x, y] : mesh_edges(b)) edges.emplace_back(x + na, y + na);
  geometry::Edges edge_matrix(static_cast<int>(edges.size()), 2);
  for (std::size_t e = 0; e < edges.size(); ++e)
    edge_matrix.row(static_cast<int>(e)) << edges[e].first, edges[e].second;
  std::vector<int> body(static_cast<std::size_t>(positions.rows()), 0);
  std::fill(body.begin() + na, body.end(), 1);
  return geometry::count_intersections(positions, faces, edge_matrix, body,
                                       [](int x, int y) { return x != y; });
}

}  // namespace grip::synth::testing
