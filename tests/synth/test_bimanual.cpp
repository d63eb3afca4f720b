// Tests of bimanual composition on synthetic one-hand candidates whose "hands" are small boxes
// at their contact centres: the farthest cluster pairs are kept, the best force-closure
// combinations within them, about the target count, and colliding hands are discarded.
#include <gtest/gtest.h>

#include <set>

#include "src/geometry/primitives.hpp"
#include "src/synth/bimanual.hpp"
#include "src/synth/candidate_random.hpp"
#include "src/synth/hand_energy.hpp"
#include "src/synth/kmeans.hpp"

namespace grip::synth {
namespace {

// One-hand candidates with two contacts around `centre` (jittered), outward sphere normals.
std::vector<Candidate> group(const Eigen::Vector3d& centre, int n, std::uint64_t seed) {
  std::vector<Candidate> out;
  CandidateRandom random(seed, 0, 0);
  for (int i = 0; i < n; ++i) {
    Candidate c;
    c.gripper = grippers::GripperKind::kParallelJaw;
    HandGrasp h;
    h.pose.translation() = centre;
    h.joints = Eigen::VectorXd::Constant(1, 0.05);
    const Eigen::Vector3d jitter(random.uniform(-0.01, 0.01), random.uniform(-0.01, 0.01),
                                 random.uniform(-0.01, 0.01));
    h.contacts.resize(2, 3);
    h.contact_normals.resize(2, 3);
    h.contacts.row(0) = (centre + jitter).transpose();
    h.contacts.row(1) = (centre - jitter + Eigen::Vector3d(0, 0, 0.002)).transpose();
    h.contact_normals = h.contacts.rowwise().normalized();
    c.hands.push_back(h);
    c.energies = {{"score", double(i)}};
    c.min_distance = 0.002;
    out.push_back(c);
  }
  return out;
}

geometry::SurfaceMesh box_at(const Candidate& c) {
  geometry::SurfaceMesh box = geometry::make_box(Eigen::Vector3d::Constant(0.01));
  box.vertices.rowwise() += c.hands[0].contacts.colwise().mean();
  return box;
}

TEST(SynthBimanualTest, KeepsTheFarthestClusterPairAndItsBestCombinations) {
  const PreparedObject object(geometry::make_sphere(0.2, 24, 12));
  // Right hands near +x or at the centre line; left hands near -x or just beside +x.
  std::vector<Candidate> right = group({0.2, 0, 0}, 10, 1), right_b = group({0.0, 0.2, 0}, 10, 2);
  std::vector<Candidate> left = group({-0.2, 0, 0}, 10, 3), left_b = group({0.1, 0.15, 0}, 10, 4);
  right.insert(right.end(), right_b.begin(), right_b.end());
  left.insert(left.end(), left_b.begin(), left_b.end());
  BimanualParams params;
  params.clusters = 2;  // k^2 = 4 pairs, r1 = 0.25 keeps the farthest one: (+x, -x)
  BimanualStatistics stats;
  const std::vector<Candidate> out = compose_bimanual(
      object, right, left, 20, params, 3, [](const Candidate& c, bool) { return box_at(c); },
      &stats);
  EXPECT_EQ(stats.filtered, 100);
  EXPECT_EQ(out.size(), 20u);
  double worst_kept = 0.0;
  std::set<std::pair<double, double>> kept;
  for (const Candidate& c : out) {
    ASSERT_EQ(c.hands.size(), 2u);
    EXPECT_GT(c.hands[0].pose.translation().x(), 0.1);   // right from the +x group
    EXPECT_LT(c.hands[1].pose.translation().x(), -0.1);  // left from the -x group
    Points3 points(4, 3), normals(4, 3);
    points << c.hands[0].contacts, c.hands[1].contacts;
    normals << c.hands[0].contact_normals, c.hands[1].contact_normals;
    points.rowwise() -= object.centroid().transpose();
    EXPECT_DOUBLE_EQ(c.energies[0].value, force_closure_error(points, normals));
    EXPECT_EQ(c.energies[1].name, "right_score");
    EXPECT_EQ(c.energies[2].name, "left_score");
    worst_kept = std::max(worst_kept, c.energies[0].value);
    kept.emplace(c.energies[1].value, c.energies[2].value);
  }
  // Every combination of the pair that was not kept is no better than the worst kept one.
  for (int r = 0; r < 10; ++r) {
    for (int l = 0; l < 10; ++l) {
      if (kept.count({double(r), double(l)})) continue;
      Points3 points(4, 3), normals(4, 3);
      points << right[static_cast<std::size_t>(r)].hands[0].contacts,
          left[static_cast<std::size_t>(l)].hands[0].contacts;
      normals << right[static_cast<std::size_t>(r)].hands[0].contact_normals,
          left[static_cast<std::size_t>(l)].hands[0].contact_normals;
      points.rowwise() -= object.centroid().transpose();
      EXPECT_GE(force_closure_error(points, normals), worst_kept);
    }
  }
}

TEST(SynthBimanualTest, DiscardsHandsThatCollide) {
  const PreparedObject object(geometry::make_sphere(0.2, 24, 12));
  // Both sides at the same place: every combination's boxes overlap.
  const std::vector<Candidate> right = group({0.2, 0, 0}, 5, 1), left = group({0.2, 0, 0}, 5, 2);
  BimanualParams params;
  params.clusters = 1;
  params.pair_fraction = 1.0;
  BimanualStatistics stats;
  const std::vector<Candidate> out = compose_bimanual(
      object, right, left, 10, params, 3, [](const Candidate& c, bool) { return box_at(c); },
      &stats);
  EXPECT_TRUE(out.empty());
  EXPECT_EQ(stats.colliding, stats.examined);
  // Colliding combinations do not count against the pair's quota: all 25 get examined.
  EXPECT_EQ(stats.examined, 25);
}

}  // namespace
}  // namespace grip::synth
