// The broad phase kept from call to call finds exactly what a fresh one finds, in the same
// order: its lazily built trees answer as whole trees, whatever was built and asked before.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "scene_builders.hpp"
#include "solver/body/body.hpp"
#include "solver/contact/bvh.hpp"
#include "solver/contact/candidates.hpp"

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

// Two kinematic jaws, an affine box between them and a soft (FEM) box on top, 1 mm apart.
SceneDescription jaws_box_and_soft_box() {
  using testing::rigid_box;
  SceneDescription scene;
  const Eigen::Vector3d size(0.02, 0.02, 0.02);
  scene.bodies = {rigid_box("left", BodyType::kKinematic, size, {-0.021, 0, 0}),
                  rigid_box("right", BodyType::kKinematic, size, {0.021, 0, 0}),
                  rigid_box("box", BodyType::kAffine, size, {0, 0, 0}),
                  testing::soft_box("soft", size, 0.01, {0, 0, 0.021}, 1e6)};
  return scene;
}

TEST(ContactBroadPhase, KeptBetweenCallsFindsWhatAFreshOneFinds) {
  const std::shared_ptr<const Model> model = Model::build(jaws_box_and_soft_box());
  const Vertices rest = Environment(model).collision_positions();
  const std::vector<int>& vertex_body = model->collision().vertex_body;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> jitter(-5e-4, 5e-4);
  ContactBroadPhase kept;
  Vertices start = rest;
  int nonempty = 0;
  for (int frame = 0; frame < 40; ++frame) {
    // Each body moves rigidly, the soft one vertex by vertex too; some frames keep the
    // kinematic bodies or everything where they were.
    std::vector<Eigen::Vector3d> motion(model->bodies().size());
    for (auto& m : motion) m = Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng));
    Vertices end = start;
    for (int v = 0; v < rest.rows(); ++v) {
      const int body = vertex_body[v];
      if (frame % 4 == 3) continue;
      if (frame % 4 == 2 && is_kinematic(model->bodies()[body])) continue;
      end.row(v) += motion[body].transpose();
      if (model->bodies()[body].type == BodyType::kFem) {
        end.row(v) += 0.2 * Eigen::RowVector3d(jitter(rng), jitter(rng), jitter(rng));
      }
    }
    const double d_hat = frame % 5 == 4 ? 3e-3 : 1.5e-3;
    const std::vector<ContactCandidate> fresh = find_contact_candidates(*model, start, end, d_hat);
    expect_same(kept.find(*model, start, end, d_hat), fresh);
    expect_same(kept.find(*model, end, end, d_hat),
                find_contact_candidates(*model, end, end, d_hat));
    nonempty += fresh.empty() ? 0 : 1;
    start = end;
  }
  EXPECT_GT(nonempty, 30);
}

}  // namespace
}  // namespace grip::solver
