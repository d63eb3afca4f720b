#include "solver/contact/candidates.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "solver/kernels/accd.hpp"
#include "solver/kernels/edge_edge_distance.hpp"
#include "solver/kernels/edge_edge_mollifier.hpp"
#include "solver/kernels/point_triangle_distance.hpp"

namespace grip::solver {
namespace {

// For each body, the bodies whose primitives its own look among: for the pairs of one body
// (own_body >= 0), that body alone, itself; for the pairs of two, the others each may touch.
std::vector<std::vector<int>> partner_bodies(const CollisionMesh& mesh, int own_body) {
  std::vector<std::vector<int>> partners(static_cast<std::size_t>(mesh.body_count()));
  if (own_body >= 0) {
    partners[own_body] = {own_body};
    return partners;
  }
  for (int a = 0; a < static_cast<int>(partners.size()); ++a) {
    for (int b = 0; b < static_cast<int>(partners.size()); ++b) {
      if (b != a && mesh.may_touch(a, b)) partners[a].push_back(b);
    }
  }
  return partners;
}

// Each vertex's triangles are listed by face index: the order of the trees' answers depends on
// their shape, which depends on the boxes they were built over.
void add_point_triangle_candidates(const CollisionMesh& mesh, int own_body,
                                   const std::vector<Aabb>& vertex_boxes, PrimitiveTrees& faces,
                                   std::vector<int>& hits, KeptPairs& kept) {
  const std::vector<std::vector<int>> partners = partner_bodies(mesh, own_body);
  for (int v = 0; v < mesh.size(); ++v) {
    const int body_v = mesh.vertex_body[v];
    if (partners[body_v].empty()) continue;
    hits.clear();
    for (const int body : partners[body_v]) {
      faces.query(body, vertex_boxes[v], [&](int f) { hits.push_back(f); });
    }
    std::sort(hits.begin(), hits.end());
    for (const int f : hits) {
      const auto& t = mesh.faces[f];
      if (t[0] == v || t[1] == v || t[2] == v) continue;
      const std::array<int, 4> pair{v, t[0], t[1], t[2]};
      kept.add({false, pair, mesh.pair_friction(body_v, mesh.vertex_body[t[0]]), 0.0,
                own_body >= 0 && mesh.near_at_rest(false, pair)},
               {v, f});
    }
  }
}

// Each unordered pair of edges once: from its lower index when both or neither are on untouching
// bodies (CollisionMesh::among_untouching), else from the untouching edge's side. Each edge's
// partners are listed by edge index.
void add_edge_edge_candidates(const CollisionMesh& mesh, int own_body, PrimitiveTrees& edges,
                              std::vector<int>& hits, KeptPairs& kept) {
  auto untouching = [&](int edge) {
    return mesh.among_untouching(mesh.vertex_body[mesh.edges[edge][0]]);
  };
  const std::vector<std::vector<int>> partners = partner_bodies(mesh, own_body);
  for (int a = 0; a < static_cast<int>(mesh.edges.size()); ++a) {
    const auto& ea = mesh.edges[a];
    const int body_a = mesh.vertex_body[ea[0]];
    if (partners[body_a].empty()) continue;
    hits.clear();
    for (const int body : partners[body_a]) {
      edges.query(body, edges.box(a), [&](int b) {
        if (b == a) return;
        if (untouching(a) == untouching(b) ? b < a : untouching(b)) return;
        hits.push_back(b);
      });
    }
    std::sort(hits.begin(), hits.end());
    for (const int b : hits) {
      const auto& eb = mesh.edges[b];
      if (ea[0] == eb[0] || ea[0] == eb[1] || ea[1] == eb[0] || ea[1] == eb[1]) continue;
      // The threshold depends on rest lengths only, so each edge may be in its own body frame.
      const double eps = kernels::edge_edge_mollifier_threshold(
          mesh.rest_position(ea[0]), mesh.rest_position(ea[1]), mesh.rest_position(eb[0]),
          mesh.rest_position(eb[1]));
      const std::array<int, 4> pair{ea[0], ea[1], eb[0], eb[1]};
      kept.add({true, pair, mesh.pair_friction(body_a, mesh.vertex_body[eb[0]]), eps,
                own_body >= 0 && mesh.near_at_rest(true, pair)},
               {a, b});
    }
  }
}

// Each face's (edge's) box: the union of its vertices' boxes.
void face_boxes(const CollisionMesh& mesh, const std::vector<Aabb>& vertex_boxes,
                std::vector<Aabb>& boxes) {
  boxes.resize(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& t = mesh.faces[f];
    boxes[f] = vertex_boxes[t[0]];
    boxes[f].expand(vertex_boxes[t[1]]);
    boxes[f].expand(vertex_boxes[t[2]]);
  }
}

void edge_boxes(const CollisionMesh& mesh, const std::vector<Aabb>& vertex_boxes,
                std::vector<Aabb>& boxes) {
  boxes.resize(mesh.edges.size());
  for (std::size_t e = 0; e < mesh.edges.size(); ++e) {
    boxes[e] = vertex_boxes[mesh.edges[e][0]];
    boxes[e].expand(vertex_boxes[mesh.edges[e][1]]);
  }
}

// The squared distance of a pair's primitives at x.
double pair_distance_sq(const ContactCandidate& c, const Vertices& x) {
  const auto at = [&](int k) -> Eigen::Vector3d { return x.row(c.vertex[k]).transpose(); };
  return c.edge_edge ? kernels::edge_edge_distance_sq(at(0), at(1), at(2), at(3))
                     : kernels::point_triangle_distance_sq(at(0), at(1), at(2), at(3));
}

// The squared distance between the boxes of the pair's two primitives at x: at most the pair's.
double pair_box_distance_sq(const ContactCandidate& c, const Vertices& x) {
  const int first_b = c.edge_edge ? 2 : 1;
  Aabb a, b;
  for (int k = 0; k < 4; ++k) (k < first_b ? a : b).expand(Eigen::Vector3d(x.row(c.vertex[k])));
  return a.distance_sq(b);
}

// The largest of `values` over each side of a pair: its point or first edge, its triangle or
// second edge (every point of a primitive moves at most as far as its farthest vertex).
std::array<double, 2> largest_per_side(const ContactCandidate& c, const Eigen::VectorXd& values) {
  const auto& v = c.vertex;
  if (c.edge_edge)
    return {std::max(values[v[0]], values[v[1]]), std::max(values[v[2]], values[v[3]])};
  return {values[v[0]], std::max({values[v[1]], values[v[2]], values[v[3]]})};
}

bool on_one_body(const std::vector<int>& vertex_body, const ContactCandidate& c) {
  return vertex_body[c.vertex[0]] == vertex_body[c.vertex[2]];
}

// Whether additive CCD of the pair from start to end answers "no impact" at its first advance
// (kernels::accd_clears_at_first_advance), d_sq its distance at the start; with a relative margin
// far above round-off, so that no rounding leaves out a pair CCD would stop at. Leaving such a
// pair out leaves the step's collision-free fraction as it was.
bool ccd_clears_at_once(const ContactCandidate& c, const Vertices& start, const Vertices& end,
                        double d_sq, double ccd_rescaling) {
  Eigen::Matrix<double, 3, 4> dx;
  for (int k = 0; k < 4; ++k) {
    dx.col(k) = (end.row(c.vertex[k]) - start.row(c.vertex[k])).transpose();
  }
  const double l_p = kernels::accd_relative_motion(dx, c.edge_edge);
  kernels::AccdOptions options;
  options.rescaling = ccd_rescaling;
  return kernels::accd_clears_at_first_advance(std::sqrt(d_sq) * (1.0 - 1e-6), l_p * (1.0 + 1e-6),
                                               options);
}

// within_reach with the displacements in each body on the path already at hand (near() has
// them for its screen).
std::vector<ContactCandidate> pairs_within_reach(const std::vector<int>& vertex_body,
                                                 const std::vector<ContactCandidate>& candidates,
                                                 const Vertices& start, const Vertices& end,
                                                 const Eigen::VectorXd& moved_in_body, double d_hat,
                                                 std::vector<ContactCandidate>* ccd,
                                                 double ccd_rescaling) {
  // Each vertex's displacement once: most vertices are in many pairs.
  const Eigen::VectorXd moved = (end - start).rowwise().norm();
  // Relative margins far above round-off keep every pair the rounding could bring in.
  const double ccd_stops_sq = ccd ? std::pow(d_hat * (1.0 - 1e-6) / ccd_rescaling, 2) : 0.0;
  std::vector<ContactCandidate> reachable;
  if (ccd) ccd->clear();
  for (const ContactCandidate& c : candidates) {
    const auto [a, b] = largest_per_side(c, on_one_body(vertex_body, c) ? moved_in_body : moved);
    const double reach = d_hat + a + b;
    // Most pairs an object flying past a gripper brings in are far on both counts, and the
    // distance of their primitives' boxes, a lower bound of theirs, says so without the exact one.
    const double lower_sq = pair_box_distance_sq(c, start);
    if (lower_sq > reach * reach * (1.0 + 1e-5) &&
        (!ccd || ccd_clears_at_once(c, start, end, lower_sq, ccd_rescaling))) {
      continue;
    }
    const double d_sq = pair_distance_sq(c, start);
    const bool within = d_sq <= reach * reach * (1.0 + 1e-6);
    if (within) reachable.push_back(c);
    const bool ccd_may_stop =
        within || (d_sq >= ccd_stops_sq && !ccd_clears_at_once(c, start, end, d_sq, ccd_rescaling));
    if (ccd && ccd_may_stop) ccd->push_back(c);
  }
  return reachable;
}

}  // namespace

void KeptPairs::clear() {
  pairs.clear();
  primitives.clear();
  order.clear();
}

void KeptPairs::add(const ContactCandidate& pair, const std::array<int, 2>& primitive_pair) {
  pairs.push_back(pair);
  primitives.push_back(primitive_pair);
  order.push_back(static_cast<std::uint64_t>(pair.edge_edge) << 62 |
                  static_cast<std::uint64_t>(primitive_pair[0]) << 31 |
                  static_cast<std::uint64_t>(primitive_pair[1]));
}

std::vector<ContactCandidate> ContactBroadPhase::find(const CollisionMesh& mesh,
                                                      const Vertices& start, const Vertices& end,
                                                      double d_hat) {
  prepare(mesh, start, end, d_hat);
  return overlapping([](std::size_t) { return false; });
}

std::vector<ContactCandidate> ContactBroadPhase::near(const CollisionMesh& mesh,
                                                      const Vertices& start, const Vertices& end,
                                                      double d_hat,
                                                      std::vector<ContactCandidate>* ccd,
                                                      double ccd_rescaling) {
  prepare(mesh, start, end, d_hat);
  // Each kept pair of one body is measured the first time its box overlaps after a keep: many
  // never do before the next keep.
  if (kept_distance_.size() != kept_.pairs.size()) {
    kept_distance_.assign(kept_.pairs.size(), kUnmeasured);
  }
  const std::vector<int>& vertex_body = mesh.vertex_body;
  const Eigen::VectorXd since_kept = displacements_in_body(vertex_body, kept_start_, start);
  const Eigen::VectorXd on_path = displacements_in_body(vertex_body, start, end);
  // within_reach's tests with a relative margin wider than theirs, so that no rounding can pass
  // over a pair they would keep.
  constexpr double kMargin = 1e-5;
  const double ccd_stop = ccd ? d_hat * (1.0 - 1e-6) / ccd_rescaling : 0.0;
  const std::vector<ContactCandidate> boxed = overlapping([&](std::size_t i) {
    if (!kept_own_[i]) return false;
    if (kept_distance_[i] == kUnmeasured) {
      kept_distance_[i] = std::sqrt(pair_distance_sq(kept_.pairs[i], kept_start_));
    }
    const double kept_distance = kept_distance_[i];
    const auto [moved_a, moved_b] = largest_per_side(kept_.pairs[i], since_kept);
    const auto [path_a, path_b] = largest_per_side(kept_.pairs[i], on_path);
    // The pair's distance at the start lies within moved_a + moved_b of its kept distance.
    const bool beyond_reach =
        kept_distance - moved_a - moved_b > (d_hat + path_a + path_b) * (1.0 + kMargin);
    const bool short_of_ccd =
        !ccd || (kept_distance + moved_a + moved_b) * (1.0 + kMargin) < ccd_stop;
    const bool skip = beyond_reach && short_of_ccd;
    screened_ += skip;
    return skip;
  });
  return pairs_within_reach(vertex_body, boxed, start, end, on_path, d_hat, ccd, ccd_rescaling);
}

void ContactBroadPhase::prepare(const CollisionMesh& mesh, const Vertices& start,
                                const Vertices& end, double d_hat) {
  // Two boxes each inflated by half of d_hat overlap whenever their contents come within d_hat.
  const double margin = 0.5 * d_hat * (1.0 + 1e-9);
  // Each vertex's swept box. A primitive's box is the union of its vertices' (inflating after
  // the union or before gives the same bits: rounding is monotonic).
  vertex_boxes_.resize(static_cast<std::size_t>(mesh.size()));
  const bool kept = kept_mesh_ == &mesh && kept_vertex_boxes_.size() == vertex_boxes_.size();
  bool kept_covers = kept;
  for (int v = 0; v < mesh.size(); ++v) {
    Aabb& box = vertex_boxes_[v];
    box = Aabb{};
    box.expand(Eigen::Vector3d(start.row(v)));
    box.expand(Eigen::Vector3d(end.row(v)));
    box.inflate(margin);
    kept_covers = kept_covers && kept_vertex_boxes_[v].contains(box);
  }
  if (!kept) {
    kept_.clear();  // another model's, or none
    kept_own_.clear();
    deformed_.assign(static_cast<std::size_t>(mesh.body_count()), 1);
    keep(mesh, start, d_hat);
  } else if (!own_pairs_cover(mesh, start, end, d_hat) || !kept_covers) {
    keep(mesh, start, d_hat);
  }
  face_boxes(mesh, vertex_boxes_, face_boxes_);
  edge_boxes(mesh, vertex_boxes_, edge_boxes_);
}

bool ContactBroadPhase::own_pairs_cover(const CollisionMesh& mesh, const Vertices& start,
                                        const Vertices& end, double d_hat) {
  const std::size_t body_count = static_cast<std::size_t>(mesh.body_count());
  // Each body's common motion since its own pairs were kept: the centre of the box of its
  // vertices' displacements.
  body_motion_.assign(body_count, Aabb{});
  for (int v = 0; v < mesh.size(); ++v) {
    body_motion_[mesh.vertex_body[v]].expand(
        Eigen::Vector3d((start.row(v) - own_start_.row(v)).transpose()));
  }
  // The moved-back boxes are rounded differently from the boxes the pairs are tested with: a
  // margin far above round-off and far below the skin covers that.
  const double margin = 0.5 * d_hat * (1.0 + 1e-6);
  deformed_.assign(body_count, 0);
  bool covers = true;
  for (int v = 0; v < mesh.size(); ++v) {
    const int body = mesh.vertex_body[v];
    if (deformed_[body] || !mesh.may_touch(body, body)) continue;
    const Eigen::Vector3d back = body_motion_[body].center();
    Aabb box;
    box.expand(Eigen::Vector3d(start.row(v).transpose() - back));
    box.expand(Eigen::Vector3d(end.row(v).transpose() - back));
    box.inflate(margin);
    if (!own_vertex_boxes_[v].contains(box)) {
      deformed_[body] = 1;
      covers = false;
    }
  }
  return covers;
}

template <typename Skip>
std::vector<ContactCandidate> ContactBroadPhase::overlapping(Skip&& skip) {
  // The kept pairs whose boxes overlap now: every pair that overlaps now, since each of its
  // boxes lies in its kept box, in the kept pairs' order.
  std::vector<ContactCandidate> candidates;
  for (std::size_t i = 0; i < kept_.pairs.size(); ++i) {
    const auto [a, b] = kept_.primitives[i];
    const bool overlap = kept_.pairs[i].edge_edge ? edge_boxes_[a].overlaps(edge_boxes_[b])
                                                  : vertex_boxes_[a].overlaps(face_boxes_[b]);
    if (overlap && !skip(i)) candidates.push_back(kept_.pairs[i]);
  }
  return candidates;
}

// The pairs of two bodies and each body's own, merged into the candidates' order.
void ContactBroadPhase::merge_kept() {
  std::vector<const KeptPairs*> lists{&two_bodies_};
  for (const KeptPairs& own : own_) {
    if (!own.pairs.empty()) lists.push_back(&own);
  }
  std::vector<std::size_t> next(lists.size(), 0);
  kept_.clear();
  kept_own_.clear();
  for (;;) {
    int first = -1;
    for (int l = 0; l < static_cast<int>(lists.size()); ++l) {
      if (next[l] < lists[l]->pairs.size() &&
          (first < 0 || lists[l]->order[next[l]] < lists[first]->order[next[first]])) {
        first = l;
      }
    }
    if (first < 0) break;
    const std::size_t i = next[first]++;
    kept_.add(lists[first]->pairs[i], lists[first]->primitives[i]);
    kept_own_.push_back(first > 0);
  }
  kept_distance_.clear();
}

// The pairs whose boxes overlap once each vertex's box is grown by the skin: they hold every pair
// of later calls whose vertex boxes stay inside these. The pairs of two bodies are kept again
// every time; a body's own only when it has deformed (deformed_).
void ContactBroadPhase::keep(const CollisionMesh& mesh, const Vertices& start, double d_hat) {
  ++keeps_;
  kept_mesh_ = &mesh;
  kept_start_ = start;
  kept_vertex_boxes_ = vertex_boxes_;
  for (Aabb& box : kept_vertex_boxes_) box.inflate(0.5 * kSkin * d_hat);
  face_boxes(mesh, kept_vertex_boxes_, boxes_);
  first_vertex_.resize(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) first_vertex_[f] = mesh.faces[f][0];
  faces_.update(mesh, boxes_, first_vertex_);
  edge_boxes(mesh, kept_vertex_boxes_, boxes_);
  first_vertex_.resize(mesh.edges.size());
  for (std::size_t e = 0; e < mesh.edges.size(); ++e) first_vertex_[e] = mesh.edges[e][0];
  edges_.update(mesh, boxes_, first_vertex_);
  const auto add_pairs = [&](int own_body, KeptPairs& kept) {
    kept.clear();
    add_point_triangle_candidates(mesh, own_body, kept_vertex_boxes_, faces_, hits_, kept);
    add_edge_edge_candidates(mesh, own_body, edges_, hits_, kept);
  };
  add_pairs(-1, two_bodies_);
  const int body_count = mesh.body_count();
  // The own pairs of the bodies that have not deformed, back from the merged list (only it is
  // kept between keeps, to spare the memory of a second copy).
  own_.assign(body_count, KeptPairs{});
  for (std::size_t i = 0; i < kept_.pairs.size(); ++i) {
    const int body = mesh.vertex_body[kept_.pairs[i].vertex[0]];
    if (kept_own_[i] && !deformed_[body]) own_[body].add(kept_.pairs[i], kept_.primitives[i]);
  }
  own_vertex_boxes_.resize(kept_vertex_boxes_.size());
  own_start_.resize(start.rows(), 3);
  for (int b = 0; b < body_count; ++b) {
    if (!deformed_[b] || !mesh.may_touch(b, b)) continue;
    ++one_body_keeps_;
    for (int v = 0; v < mesh.size(); ++v) {
      if (mesh.vertex_body[v] != b) continue;
      own_vertex_boxes_[v] = kept_vertex_boxes_[v];
      own_start_.row(v) = start.row(v);
    }
    add_pairs(b, own_[b]);
  }
  merge_kept();
  own_ = {};
  two_bodies_ = {};
}

std::vector<ContactCandidate> within_reach(const std::vector<int>& vertex_body,
                                           const std::vector<ContactCandidate>& candidates,
                                           const Vertices& start, const Vertices& end, double d_hat,
                                           std::vector<ContactCandidate>* ccd,
                                           double ccd_rescaling) {
  return pairs_within_reach(vertex_body, candidates, start, end,
                            displacements_in_body(vertex_body, start, end), d_hat, ccd,
                            ccd_rescaling);
}

Eigen::VectorXd displacements_in_body(const std::vector<int>& vertex_body, const Vertices& from,
                                      const Vertices& to) {
  std::vector<Aabb> shared(
      vertex_body.empty() ? 0 : *std::max_element(vertex_body.begin(), vertex_body.end()) + 1);
  for (Eigen::Index v = 0; v < from.rows(); ++v) {
    shared[vertex_body[v]].expand(Eigen::Vector3d((to.row(v) - from.row(v)).transpose()));
  }
  Eigen::VectorXd moved(from.rows());
  for (Eigen::Index v = 0; v < from.rows(); ++v) {
    moved[v] = (to.row(v) - from.row(v) - shared[vertex_body[v]].center().transpose()).norm();
  }
  return moved;
}

std::vector<ContactCandidate> find_contact_candidates(const CollisionMesh& mesh,
                                                      const Vertices& start, const Vertices& end,
                                                      double d_hat) {
  return ContactBroadPhase().find(mesh, start, end, d_hat);
}

std::pair<std::vector<std::array<int, 4>>, std::vector<std::array<int, 4>>> self_pairs_near_at_rest(
    const CollisionMesh& mesh, double d_hat) {
  // Only pairs of one body are kept, and only a body that deforms touches itself; its rest
  // vertices are all in the world frame.
  std::vector<std::array<int, 4>> point_triangle, edge_edge;
  for (const ContactCandidate& c : find_contact_candidates(mesh, mesh.rest, mesh.rest, d_hat)) {
    const int body = mesh.vertex_body[c.vertex[0]];
    if (std::any_of(c.vertex.begin(), c.vertex.end(),
                    [&](int v) { return mesh.vertex_body[v] != body; })) {
      continue;
    }
    if (pair_distance_sq(c, mesh.rest) < d_hat * d_hat)
      (c.edge_edge ? edge_edge : point_triangle).push_back(c.vertex);
  }
  std::sort(point_triangle.begin(), point_triangle.end());
  std::sort(edge_edge.begin(), edge_edge.end());
  return {std::move(point_triangle), std::move(edge_edge)};
}

}  // namespace grip::solver
