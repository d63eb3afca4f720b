// Environment's read-only views of its state: positions, centres of mass, rotations, volumes
// and contact forces, between steps.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "solver/contact/bvh.hpp"
#include "solver/environment.hpp"
#include "solver/kernels/aabb.hpp"
#include "solver/kernels/edge_edge_distance.hpp"
#include "solver/kernels/point_triangle_distance.hpp"

namespace grip::solver {

namespace {

// The nearest pair between two sets of bodies, found as find_contact_candidates finds pairs
// (bodies that may touch, no shared vertex) and with each pair's vertices in its order (an
// edge-edge pair from the untouching edge, Model::among_untouching, else from the lower edge
// index), so that each distance has the same bits. Boxes are the vertices' inflated by `margin`: a
// pair whose boxes miss is farther than twice the margin, where the caller looks no more.
struct SurfacePairs {
  const Model& model;
  const Vertices& x;
  double margin;

  int body(int v) const { return model.collision().vertex_body[static_cast<std::size_t>(v)]; }
  bool untouching(int v) const { return model.among_untouching(body(v)); }
  bool may_touch(int v, int w) const { return model.may_touch(body(v), body(w)); }
  Eigen::Vector3d p(int v) const { return x.row(v).transpose(); }
  Aabb vertex_box(int v) const {
    Aabb box;
    box.expand(p(v));
    box.inflate(margin);
    return box;
  }
  template <typename Primitive>
  Aabb box(const Primitive& vertices) const {
    Aabb box;
    for (int v : vertices) box.expand(vertex_box(v));
    return box;
  }
  // A tree over the primitives of the bodies `keep` selects; index maps its boxes back.
  template <typename Primitives, typename Keep>
  void tree(const Primitives& primitives, Keep keep, std::vector<int>& index,
            std::vector<Aabb>& boxes, Bvh& tree) const {
    for (int i = 0; i < static_cast<int>(primitives.size()); ++i) {
      if (!keep(body(primitives[static_cast<std::size_t>(i)][0]))) continue;
      index.push_back(i);
      boxes.push_back(box(primitives[static_cast<std::size_t>(i)]));
    }
    tree.build(boxes);
  }

  // Squared distance of the nearest point-triangle pair, points of `points`, faces of `faces`.
  template <typename Points, typename Faces>
  double nearest_point_triangle_sq(Points points, Faces faces) const {
    const auto& all = model.collision().faces;
    std::vector<int> index;
    std::vector<Aabb> boxes;
    Bvh face_tree;
    tree(all, faces, index, boxes, face_tree);
    double nearest = std::numeric_limits<double>::infinity();
    for (int v = 0; v < model.collision().size(); ++v) {
      if (!points(body(v))) continue;
      face_tree.query(vertex_box(v), [&](int k) {
        const auto& t = all[static_cast<std::size_t>(index[static_cast<std::size_t>(k)])];
        if (t[0] == v || t[1] == v || t[2] == v || !may_touch(v, t[0])) return;
        nearest =
            std::min(nearest, kernels::point_triangle_distance_sq(p(v), p(t[0]), p(t[1]), p(t[2])));
      });
    }
    return nearest;
  }

  // Squared distance of the nearest edge-edge pair between the bodies of `first` and `second`.
  template <typename First, typename Second>
  double nearest_edge_edge_sq(First first, Second second) const {
    const auto& edges = model.collision().edges;
    std::vector<int> index;
    std::vector<Aabb> boxes;
    Bvh edge_tree;
    tree(edges, second, index, boxes, edge_tree);
    double nearest = std::numeric_limits<double>::infinity();
    for (int a = 0; a < static_cast<int>(edges.size()); ++a) {
      if (!first(body(edges[static_cast<std::size_t>(a)][0]))) continue;
      edge_tree.query(box(edges[static_cast<std::size_t>(a)]), [&](int k) {
        int i = a, j = index[static_cast<std::size_t>(k)];
        const bool untouching_j = untouching(edges[static_cast<std::size_t>(j)][0]);
        if (untouching(edges[static_cast<std::size_t>(i)][0]) == untouching_j ? j < i
                                                                              : untouching_j) {
          std::swap(i, j);
        }
        const auto& ea = edges[static_cast<std::size_t>(i)];
        const auto& eb = edges[static_cast<std::size_t>(j)];
        if (i == j || ea[0] == eb[0] || ea[0] == eb[1] || ea[1] == eb[0] || ea[1] == eb[1] ||
            !may_touch(ea[0], eb[0])) {
          return;
        }
        nearest = std::min(nearest,
                           kernels::edge_edge_distance_sq(p(ea[0]), p(ea[1]), p(eb[0]), p(eb[1])));
      });
    }
    return nearest;
  }
};

}  // namespace

Vertices Environment::collision_positions() const {
  return solver::collision_positions(*model_, state_.q, targets_at_rest(*model_, state_), 0.0);
}

Vertices Environment::body_vertices(int index) const {
  const BodyModel& body = model_->bodies()[index];
  std::vector<int> all(static_cast<std::size_t>(body.kind->vertex_count(body.local)));
  std::iota(all.begin(), all.end(), 0);
  Vertices x(static_cast<Eigen::Index>(all.size()), 3);
  body.kind->vertex_positions(body.local, state_.q, state_.poses[index], all, x, 0);
  return x;
}

Eigen::Vector3d Environment::center_of_mass(int index) const {
  const BodyModel& body = model_->bodies()[index];
  return body.kind->center_of_mass(body.local, state_);
}

Eigen::Vector3d Environment::center_of_mass_velocity(int index) const {
  const BodyModel& body = model_->bodies()[index];
  return body.kind->center_of_mass_velocity(body.local, state_);
}

Eigen::Matrix3d Environment::rotation(int index) const {
  const BodyModel& body = model_->bodies()[index];
  return body.kind->rotation(body.local, state_);
}

double Environment::min_volume_ratio() const { return model_->min_volume_ratio(state_.q); }

VertexContactForces Environment::vertex_contact_forces() {
  const Vertices x = collision_positions();
  const std::vector<ContactCandidate> near =
      newton_.broad_phase().find(model_->collision(), x, x, model_->sim().d_hat);
  return solver::vertex_contact_forces(*model_, newton_.potential(), x, near);
}

// Only pairs between the set and `other` count, so only their primitives are searched
// (SurfacePairs): the same pairs' distances as the whole broad phase's, the same bits.
double Environment::surface_distance(const std::vector<int>& bodies, int other,
                                     double search) const {
  const Vertices x = collision_positions();
  std::vector<char> in_set(model_->bodies().size(), 0);
  for (int b : bodies) in_set[static_cast<std::size_t>(b)] = 1;
  const auto is_in_set = [&](int body) { return in_set[static_cast<std::size_t>(body)] != 0; };
  const auto is_other = [&](int body) { return body == other; };
  const SurfacePairs pairs{*model_, x, 0.5 * search * (1.0 + 1e-9)};
  const double nearest = std::sqrt(std::min({pairs.nearest_point_triangle_sq(is_in_set, is_other),
                                             pairs.nearest_point_triangle_sq(is_other, is_in_set),
                                             pairs.nearest_edge_edge_sq(is_in_set, is_other)}));
  return nearest < search ? nearest : std::numeric_limits<double>::infinity();
}

}  // namespace grip::solver
