// Environment::surface_distance searches only the two sides' primitives: it must give the very
// bits of the minimum over the whole broad phase's pairs between them, for soft, rigid and
// kinematic bodies, edge-edge and point-triangle nearest pairs, and none within the search.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "solver/contact/candidates.hpp"
#include "solver/kernels/edge_edge_distance.hpp"
#include "solver/kernels/point_triangle_distance.hpp"
#include "tests/solver/scene_builders.hpp"

namespace grip::solver::testing {
namespace {

// The distance as the whole broad phase gives it: every pair it finds within `search`.
double distance_over_all_pairs(const Environment& env, const std::vector<int>& bodies, int other,
                               double search) {
  const Vertices x = env.collision_positions();
  const std::vector<int>& vertex_body = env.model().collision().vertex_body;
  const auto in_set = [&](int v) {
    return std::find(bodies.begin(), bodies.end(), vertex_body[v]) != bodies.end();
  };
  double nearest_sq = std::numeric_limits<double>::infinity();
  for (const ContactCandidate& c : find_contact_candidates(env.model().collision(), x, x, search)) {
    const int a = c.vertex[0], b = c.vertex[c.edge_edge ? 2 : 1];
    if (!((in_set(a) && vertex_body[b] == other) || (in_set(b) && vertex_body[a] == other))) {
      continue;
    }
    const auto p = [&](int k) -> Eigen::Vector3d { return x.row(c.vertex[k]).transpose(); };
    nearest_sq = std::min(
        nearest_sq, c.edge_edge ? kernels::edge_edge_distance_sq(p(0), p(1), p(2), p(3))
                                : kernels::point_triangle_distance_sq(p(0), p(1), p(2), p(3)));
  }
  const double nearest = std::sqrt(nearest_sq);
  return nearest < search ? nearest : std::numeric_limits<double>::infinity();
}

TEST(SurfaceDistance, EqualsTheMinimumOverTheWholeBroadPhase) {
  int finite = 0;
  for (int layout = 0; layout < 12; ++layout) {
    // A soft box, a rigid box turned about two axes and a kinematic box, at gaps of 0.3-9 mm.
    const double gap = 3e-4 * std::pow(1.4, layout);
    SceneDescription scene;
    BodyDescription rigid =
        rigid_box("rigid", BodyType::kAffine, {0.03, 0.02, 0.025}, {0.04 + gap, 0.001 * layout, 0});
    rigid.pose.rotation = Eigen::AngleAxisd(0.3 + 0.1 * layout, Eigen::Vector3d::UnitZ()) *
                          Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitX());
    scene.bodies = {
        soft_box("soft", {0.04, 0.03, 0.03}, 0.01, {0, 0, 0}, 1e6), rigid,
        rigid_box("kinematic", BodyType::kKinematic, {0.02, 0.02, 0.02}, {0, 0.025 + gap, 0})};
    const Environment env(Model::build(scene));
    for (const double search : {0.002, 0.02}) {
      for (const auto& [bodies, other] : std::vector<std::pair<std::vector<int>, int>>{
               {{0}, 1}, {{1}, 0}, {{0}, 2}, {{2}, 0}, {{0, 2}, 1}, {{1}, 2}}) {
        const double expected = distance_over_all_pairs(env, bodies, other, search);
        EXPECT_EQ(env.surface_distance(bodies, other, search), expected)
            << "layout " << layout << ", search " << search << ", other " << other;
        finite += std::isfinite(expected);
      }
    }
  }
  EXPECT_GT(finite, 40);
}

}  // namespace
}  // namespace grip::solver::testing
