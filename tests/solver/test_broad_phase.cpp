// The broad phase kept from call to call finds exactly what a fresh one finds, in the same
// order: its lazily built trees answer as whole trees, whatever was built and asked before, and
// the pairs it keeps between calls (grown by a skin) hold every pair of a call that stays inside
// their boxes.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <tuple>
#include <vector>

#include "scene_builders.hpp"
#include "solver/contact/bvh.hpp"
#include "solver/contact/candidates.hpp"
#include "solver/kernels/accd.hpp"
#include "solver/kernels/edge_edge_distance.hpp"
#include "solver/kernels/point_triangle_distance.hpp"
#include "solver/newton/line_search.hpp"

namespace grip::solver {
namespace {

std::vector<int> found(Bvh& bvh, const Aabb& query) {
  std::vector<int> hits;
  bvh.query(query, [&](int i) { hits.push_back(i); });
  return hits;
}

Aabb random_box(std::mt19937& rng, double size) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Aabb box;
  box.expand(Eigen::Vector3d(unit(rng), unit(rng), unit(rng)));
  box.inflate(size * unit(rng));
  return box;
}

TEST(Bvh, LazyTreeAnswersAsTheWholeTreeOverMovingBoxes) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> jitter(-1e-3, 1e-3);
  for (const int count : {1, 4, 5, 9, 300}) {
    std::vector<Aabb> boxes;
    for (int i = 0; i < count; ++i) boxes.push_back(random_box(rng, 0.02));
    Bvh kept;
    for (int frame = 0; frame < 20; ++frame) {
      // Some frames move every box, some a tenth of them, some none.
      for (int i = 0; i < count; ++i) {
        if (frame % 3 == 2 || (frame % 3 == 1 && i % 10 != 0)) continue;
        const Eigen::Vector3d shift(jitter(rng), jitter(rng), jitter(rng));
        boxes[i].min += shift;
        boxes[i].max += shift;
      }
      std::vector<Aabb> queries;
      for (int q = 0; q < 30; ++q) queries.push_back(random_box(rng, 0.1));
      Aabb everything;
      everything.expand(Eigen::Vector3d::Constant(-1.0));
      everything.expand(Eigen::Vector3d::Constant(2.0));
      // The whole tree: a first query reaching every node builds all of it.
      Bvh whole;
      whole.build(boxes);
      const std::vector<int> all = found(whole, everything);
      ASSERT_EQ(static_cast<int>(all.size()), count);
      kept.build(boxes);
      for (int q = static_cast<int>(queries.size()) - 1; q >= 0; --q) {
        const std::vector<int> hits = found(kept, queries[q]);
        EXPECT_EQ(hits, found(whole, queries[q])) << count << " boxes, frame " << frame;
        std::vector<int> brute;
        for (int i = 0; i < count; ++i) {
          if (boxes[i].overlaps(queries[q])) brute.push_back(i);
        }
        std::vector<int> sorted = hits;
        std::sort(sorted.begin(), sorted.end());
        EXPECT_EQ(sorted, brute);
      }
      EXPECT_EQ(found(kept, everything), all);
    }
  }
}

void expect_same(const std::vector<ContactCandidate>& a, const std::vector<ContactCandidate>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].edge_edge, b[i].edge_edge) << i;
    EXPECT_EQ(a[i].vertex, b[i].vertex) << i;
    EXPECT_EQ(a[i].friction, b[i].friction) << i;
    EXPECT_EQ(a[i].mollifier_eps, b[i].mollifier_eps) << i;
    EXPECT_EQ(a[i].near_at_rest, b[i].near_at_rest) << i;
  }
}

using SortedPair = std::pair<bool, std::array<int, 4>>;

// An edge-edge pair's two edges in ascending order.
SortedPair normalized(bool edge_edge, std::array<int, 4> v) {
  if (edge_edge && std::make_pair(v[2], v[3]) < std::make_pair(v[0], v[1])) {
    v = {v[2], v[3], v[0], v[1]};
  }
  return {edge_edge, v};
}

// Every pair the broad phase promises, by brute force over all pairs of primitives, sorted.
std::vector<SortedPair> brute_force(const Model& model, const Vertices& start, const Vertices& end,
                                    double d_hat) {
  const CollisionMesh& mesh = model.collision();
  const auto box = [&](std::initializer_list<int> vertices) {
    Aabb b;
    for (int v : vertices) {
      b.expand(Eigen::Vector3d(start.row(v)));
      b.expand(Eigen::Vector3d(end.row(v)));
    }
    b.inflate(0.5 * d_hat * (1.0 + 1e-9));
    return b;
  };
  std::vector<SortedPair> pairs;
  for (int v = 0; v < mesh.size(); ++v) {
    for (const auto& t : mesh.faces) {
      if (t[0] == v || t[1] == v || t[2] == v) continue;
      if (!model.may_touch(mesh.vertex_body[v], mesh.vertex_body[t[0]])) continue;
      if (box({v}).overlaps(box({t[0], t[1], t[2]})))
        pairs.push_back({false, {v, t[0], t[1], t[2]}});
    }
  }
  for (std::size_t a = 0; a < mesh.edges.size(); ++a) {
    for (std::size_t b = a + 1; b < mesh.edges.size(); ++b) {
      const auto &ea = mesh.edges[a], &eb = mesh.edges[b];
      if (ea[0] == eb[0] || ea[0] == eb[1] || ea[1] == eb[0] || ea[1] == eb[1]) continue;
      if (!model.may_touch(mesh.vertex_body[ea[0]], mesh.vertex_body[eb[0]])) continue;
      if (box({ea[0], ea[1]}).overlaps(box({eb[0], eb[1]}))) {
        pairs.push_back(normalized(true, {ea[0], ea[1], eb[0], eb[1]}));
      }
    }
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

// The documented order: point-triangle pairs by vertex then face index, then edge-edge pairs by
// query edge then partner edge index.
void expect_in_mesh_order(const Model& model, const std::vector<ContactCandidate>& candidates) {
  const CollisionMesh& mesh = model.collision();
  std::map<std::array<int, 3>, int> face_index;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    face_index[mesh.faces[f]] = static_cast<int>(f);
  std::map<std::array<int, 2>, int> edge_index;
  for (std::size_t e = 0; e < mesh.edges.size(); ++e)
    edge_index[mesh.edges[e]] = static_cast<int>(e);
  std::vector<std::tuple<bool, int, int>> keys;
  for (const ContactCandidate& c : candidates) {
    const auto& v = c.vertex;
    keys.emplace_back(
        c.edge_edge, c.edge_edge ? edge_index.at({v[0], v[1]}) : v[0],
        c.edge_edge ? edge_index.at({v[2], v[3]}) : face_index.at({v[1], v[2], v[3]}));
  }
  EXPECT_TRUE(std::is_sorted(keys.begin(), keys.end()));
}

bool same_pair(const ContactCandidate& a, const ContactCandidate& b) {
  return a.edge_edge == b.edge_edge && a.vertex == b.vertex;
}

// within_reach keeps, in order, every pair that comes within d_hat somewhere on the path (sampled
// at 21 points), and for CCD every pair additive CCD would stop at; returns how many it left out.
int expect_within_reach_keeps_what_comes_near(const std::vector<int>& vertex_body,
                                              const std::vector<ContactCandidate>& candidates,
                                              const Vertices& start, const Vertices& end,
                                              double d_hat) {
  const double rescaling = 0.1;
  std::vector<ContactCandidate> watched;
  const std::vector<ContactCandidate> reachable =
      within_reach(vertex_body, candidates, start, end, d_hat, &watched, rescaling);
  EXPECT_EQ(within_reach(vertex_body, candidates, start, end, d_hat).size(), reachable.size());
  std::size_t next = 0, next_watched = 0;
  for (const ContactCandidate& c : candidates) {
    const bool kept = next < reachable.size() && same_pair(reachable[next], c);
    const bool is_watched = next_watched < watched.size() && same_pair(watched[next_watched], c);
    EXPECT_TRUE(is_watched || !kept) << "a pair within reach is watched by CCD";
    next += kept;
    next_watched += is_watched;
    const auto at = [&](int i, double t) -> Eigen::Vector3d {
      return ((1.0 - t) * start.row(c.vertex[i]) + t * end.row(c.vertex[i])).transpose();
    };
    if (!is_watched) {
      kernels::AccdOptions options;
      options.rescaling = rescaling;
      const kernels::AccdResult impact =
          c.edge_edge
              ? kernels::edge_edge_accd(at(0, 0), at(1, 0), at(2, 0), at(3, 0), at(0, 1), at(1, 1),
                                        at(2, 1), at(3, 1), options)
              : kernels::point_triangle_accd(at(0, 0), at(1, 0), at(2, 0), at(3, 0), at(0, 1),
                                             at(1, 1), at(2, 1), at(3, 1), options);
      EXPECT_FALSE(impact.impact) << "CCD would stop at a pair it does not watch";
    }
    if (kept) continue;
    for (int k = 0; k <= 20; ++k) {
      const double t = k / 20.0;
      const double d_sq =
          c.edge_edge ? kernels::edge_edge_distance_sq(at(0, t), at(1, t), at(2, t), at(3, t))
                      : kernels::point_triangle_distance_sq(at(0, t), at(1, t), at(2, t), at(3, t));
      EXPECT_GE(d_sq, d_hat * d_hat) << "a pair left out comes within d_hat at t = " << t;
    }
  }
  EXPECT_EQ(next, reachable.size()) << "within_reach keeps the candidates' order";
  EXPECT_EQ(next_watched, watched.size()) << "and so does the pairs CCD watches";
  return static_cast<int>(candidates.size() - watched.size());
}

std::vector<SortedPair> as_sorted(const std::vector<ContactCandidate>& candidates) {
  std::vector<SortedPair> pairs;
  for (const ContactCandidate& c : candidates) pairs.push_back(normalized(c.edge_edge, c.vertex));
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

// Two kinematic jaws and an affine box between them, 1 mm apart; with `soft`, a soft (FEM) box
// on top of it too.
SceneDescription jaws_and_boxes(bool soft) {
  using testing::rigid_box;
  SceneDescription scene;
  const Eigen::Vector3d size(0.02, 0.02, 0.02);
  scene.bodies = {rigid_box("left", BodyType::kKinematic, size, {-0.021, 0, 0}),
                  rigid_box("right", BodyType::kKinematic, size, {0.021, 0, 0}),
                  rigid_box("box", BodyType::kAffine, size, {0, 0, 0})};
  if (soft) scene.bodies.push_back(testing::soft_box("soft", size, 0.01, {0, 0, 0.021}, 1e6));
  return scene;
}

// Returns how many kept pairs whose boxes overlap near() passed over by their kept distance.
long expect_kept_finds_what_fresh_finds(const SceneDescription& scene) {
  const std::shared_ptr<const Model> model = Model::build(scene);
  const Vertices rest = Environment(model).collision_positions();
  const std::vector<int>& vertex_body = model->collision().vertex_body;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> jitter(-5e-4, 5e-4);
  ContactBroadPhase kept;
  ContactBroadPhase screening;  // near() only
  Vertices start = rest;
  int nonempty = 0;
  int calls = 0;
  int dropped = 0;
  for (int frame = 0; frame < 40; ++frame) {
    // Each body moves rigidly, the soft one vertex by vertex too; some frames keep the
    // kinematic bodies or everything where they were.
    std::vector<Eigen::Vector3d> motion(model->bodies().size());
    for (auto& m : motion) m = Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng));
    Vertices end = start;
    for (int v = 0; v < rest.rows(); ++v) {
      const int body = vertex_body[v];
      if (frame % 4 == 3) continue;
      if (frame % 4 == 2 && !model->bodies()[body].has_dofs()) continue;
      end.row(v) += motion[body].transpose();
      if (model->bodies()[body].deforms()) {
        end.row(v) += 0.2 * Eigen::RowVector3d(jitter(rng), jitter(rng), jitter(rng));
      }
    }
    const double d_hat = frame % 5 == 4 ? 3e-3 : 1.5e-3;
    const std::vector<ContactCandidate> fresh =
        find_contact_candidates(model->collision(), start, end, d_hat);
    expect_same(kept.find(model->collision(), start, end, d_hat), fresh);
    EXPECT_EQ(as_sorted(fresh), brute_force(*model, start, end, d_hat)) << "frame " << frame;
    expect_in_mesh_order(*model, fresh);
    dropped += expect_within_reach_keeps_what_comes_near(vertex_body, fresh, start, end, d_hat);
    // near() is within_reach of what a fresh broad phase finds, both lists, in order.
    std::vector<ContactCandidate> watched, fresh_watched;
    expect_same(screening.near(model->collision(), start, end, d_hat, &watched, 0.1),
                within_reach(vertex_body, fresh, start, end, d_hat, &fresh_watched, 0.1));
    expect_same(watched, fresh_watched);
    expect_same(
        screening.near(model->collision(), end, end, d_hat),
        within_reach(vertex_body, find_contact_candidates(model->collision(), end, end, d_hat), end,
                     end, d_hat));
    expect_same(kept.find(model->collision(), end, end, d_hat),
                find_contact_candidates(model->collision(), end, end, d_hat));
    calls += 2;
    nonempty += fresh.empty() ? 0 : 1;
    start = end;
  }
  EXPECT_GT(nonempty, 30);
  // Motions of up to 0.6 mm a frame against a skin of d_hat: most calls reuse the kept pairs,
  // some (after a larger motion, with a larger d_hat) query the trees again.
  EXPECT_GE(kept.keeps(), 3);
  EXPECT_GT(dropped, 0);
  EXPECT_LT(kept.keeps(), calls / 2);
  return screening.screened();
}

TEST(ContactBroadPhase, KeptBetweenCallsFindsWhatAFreshOneFinds) {
  expect_kept_finds_what_fresh_finds(jaws_and_boxes(true));
  // Only kinematic bodies and one rigid body: no edge of the free body looks among the others.
  expect_kept_finds_what_fresh_finds(jaws_and_boxes(false));
}

// A soft plate 2 mm thick on 2 mm cells, as a fin-ray finger's walls are: its two faces, and the
// non-adjacent primitives of one face, are kept pairs that its motion as a whole never brings
// nearer. near() passes over most of those whose boxes overlap by their kept distance (244,000
// over its 80 calls) and still gives what within_reach gives over a fresh broad phase's pairs.
TEST(ContactBroadPhase, NearPassesOverPairsOfOneBodyItsMotionCannotBringNear) {
  SceneDescription scene = jaws_and_boxes(false);
  scene.bodies.push_back(
      testing::soft_box("plate", {0.02, 0.02, 0.002}, 0.002, {0, 0, 0.0125}, 1e6));
  EXPECT_GT(expect_kept_finds_what_fresh_finds(scene), 100000);
}

// Two soft plates' own pairs, most of the scene's, are kept again only when their plate deforms:
// moved as a whole by more than the skin on every path, the plates keep the pairs of two bodies
// again for every path and their own once each; one bent (a vertex pushed 2 mm), its own are kept
// again, the other's not. Each call still finds what a fresh broad phase finds, in order.
TEST(ContactBroadPhase, KeepsTheOwnPairsOfABodyAgainOnlyWhenItDeforms) {
  SceneDescription scene = jaws_and_boxes(false);
  scene.bodies.push_back(
      testing::soft_box("plate", {0.02, 0.02, 0.002}, 0.002, {0, 0, 0.0125}, 1e6));
  scene.bodies.push_back(
      testing::soft_box("under", {0.02, 0.02, 0.002}, 0.002, {0, 0, -0.0125}, 1e6));
  const std::shared_ptr<const Model> model = Model::build(scene);
  const std::vector<int>& vertex_body = model->collision().vertex_body;
  const int plate = 3, under = 4;
  Vertices start = Environment(model).collision_positions();
  const double d_hat = 1.5e-3;
  ContactBroadPhase kept;
  const auto expect_fresh = [&](const Vertices& end) {
    expect_same(kept.find(model->collision(), start, end, d_hat),
                find_contact_candidates(model->collision(), start, end, d_hat));
    std::vector<ContactCandidate> watched, fresh_watched;
    expect_same(
        kept.near(model->collision(), start, end, d_hat, &watched, 0.1),
        within_reach(vertex_body, find_contact_candidates(model->collision(), start, end, d_hat),
                     start, end, d_hat, &fresh_watched, 0.1));
    expect_same(watched, fresh_watched);
  };
  int calls = 0;
  for (int k = 0; k < 6; ++k) {
    Vertices end = start;
    for (int v = 0; v < end.rows(); ++v) {
      if (vertex_body[v] == plate) end.row(v) += Eigen::RowVector3d(0.002, -0.001, 0.0005);
      if (vertex_body[v] == under) end.row(v) += Eigen::RowVector3d(-0.0015, 0.0, -0.001);
    }
    expect_fresh(end);
    start = end;
    ++calls;
  }
  EXPECT_EQ(kept.keeps(), calls) << "each path leaves the boxes kept on the last one";
  EXPECT_EQ(kept.one_body_keeps(), 2) << "each plate's own pairs, once";
  int bent = -1;
  for (int v = 0; v < start.rows() && bent < 0; ++v) bent = vertex_body[v] == plate ? v : -1;
  Vertices end = start;
  end(bent, 2) += 0.002;
  expect_fresh(end);
  EXPECT_EQ(kept.one_body_keeps(), 3) << "the bent plate's again, not the other's";
}

// Driven jaws of one collision group are untouching, as kinematic ones are; with a kinematic
// body outside the group that they may touch, only the kinematic one is. Both find what brute
// force finds.
TEST(ContactBroadPhase, ACollisionGroupLooksOnlyAmongTheOthers) {
  SceneDescription scene = jaws_and_boxes(false);
  for (int jaw : {0, 1}) {
    scene.bodies[jaw].type = BodyType::kAffine;
    scene.bodies[jaw].drive_stiffness = 1e5;
    scene.bodies[jaw].collision_group = 0;
  }
  const std::shared_ptr<const Model> grouped = Model::build(scene);
  EXPECT_TRUE(grouped->among_untouching(0) && grouped->among_untouching(1));
  EXPECT_FALSE(grouped->among_untouching(2));
  expect_kept_finds_what_fresh_finds(scene);

  scene.bodies.push_back(
      testing::rigid_box("floor", BodyType::kKinematic, {0.1, 0.1, 0.01}, {0, 0, -0.0155}));
  const std::shared_ptr<const Model> mixed = Model::build(scene);
  EXPECT_FALSE(mixed->among_untouching(0) || mixed->among_untouching(1));
  EXPECT_TRUE(mixed->among_untouching(3));
  expect_kept_finds_what_fresh_finds(scene);
}

// A point closing on a triangle from 20 cm to 1.5 mm in one step never comes within d_hat (1 mm),
// but additive CCD (rescaling 0.1) stops it once it has closed 90 % of its gap: CCD watches it.
// From 8 mm to 1.5 mm it neither comes within d_hat nor reaches CCD's stop: neither list has it.
TEST(WithinReach, CcdWatchesTheFarPairsItWouldStop) {
  const double d_hat = 1e-3;
  Vertices start(8, 3), end(8, 3);
  for (const int first : {0, 4}) {
    const double height = first == 0 ? 0.2 : 0.008;
    start.row(first) << 0.0, 0.0, height;
    end.row(first) << 0.0, 0.0, 0.0015;
    start.row(first + 1) << -0.1, -0.1, 0.0;
    start.row(first + 2) << 0.1, -0.1, 0.0;
    start.row(first + 3) << 0.0, 0.1, 0.0;
    for (int k = 1; k <= 3; ++k) end.row(first + k) = start.row(first + k);
  }
  const std::vector<ContactCandidate> pairs{{false, {0, 1, 2, 3}, 0.5, 0.0, false},
                                            {false, {4, 5, 6, 7}, 0.5, 0.0, false}};
  std::vector<ContactCandidate> watched;
  // Each point on a body of its own, each triangle on another.
  const std::vector<int> vertex_body{0, 1, 1, 1, 2, 3, 3, 3};
  EXPECT_TRUE(within_reach(vertex_body, pairs, start, end, d_hat, &watched, 0.1).empty());
  ASSERT_EQ(watched.size(), 1u);
  EXPECT_EQ(watched[0].vertex[0], 0);
  kernels::AccdOptions options;
  options.rescaling = 0.1;
  const auto accd = [&](int first) {
    const auto s = [&](int k) -> Eigen::Vector3d { return start.row(first + k).transpose(); };
    const auto e = [&](int k) -> Eigen::Vector3d { return end.row(first + k).transpose(); };
    return kernels::point_triangle_accd(s(0), s(1), s(2), s(3), e(0), e(1), e(2), e(3), options);
  };
  EXPECT_TRUE(accd(0).impact);
  EXPECT_FALSE(accd(4).impact);
}

// A box flying 1 cm in one step past (and, in the second motion, into) a finely meshed plate:
// its swept boxes overlap thousands of the plate's primitives that CCD's first advance clears,
// and CCD watches only the others; the step's collision-free fraction is the same bit for bit
// over the pairs it watches as over every pair whose boxes overlap.
TEST(WithinReach, CcdLeavesOutThePairsItsFirstAdvanceClears) {
  SceneDescription scene;
  scene.bodies = {testing::soft_box("plate", {0.04, 0.04, 0.002}, 0.002, {0, 0, 0}, 1e6),
                  testing::rigid_box("box", BodyType::kAffine, {0.02, 0.02, 0.02}, {0, 0, 0.016})};
  const std::shared_ptr<const Model> model = Model::build(scene);
  const Vertices start = Environment(model).collision_positions();
  const std::vector<int>& vertex_body = model->collision().vertex_body;
  const double d_hat = 1e-3;
  for (const Eigen::Vector3d& motion :
       {Eigen::Vector3d(0.01, 0.0, 0.0), Eigen::Vector3d(0.004, 0.0, -0.01)}) {
    Vertices end = start;
    for (int v = 0; v < start.rows(); ++v) {
      if (vertex_body[v] == 1) end.row(v) += motion.transpose();
    }
    const std::vector<ContactCandidate> candidates =
        find_contact_candidates(model->collision(), start, end, d_hat);
    std::vector<ContactCandidate> watched;
    within_reach(vertex_body, candidates, start, end, d_hat, &watched, 0.1);
    // Flying past, no pair of the 7,896 comes near CCD's stop; flying into the plate, the pairs
    // of the faces that meet do (3,018 of 11,632).
    EXPECT_GT(candidates.size(), 5000u);
    if (motion.z() < 0.0) {
      EXPECT_LT(2 * watched.size(), candidates.size());
    } else {
      EXPECT_TRUE(watched.empty());
    }
    const double alpha = collision_free_fraction(watched, start, end, 0.1);
    EXPECT_EQ(alpha, collision_free_fraction(candidates, start, end, 0.1));
    EXPECT_EQ(alpha < 1.0, motion.z() < 0.0) << "the box flies past, or into the plate";
  }
}

}  // namespace
}  // namespace grip::solver
