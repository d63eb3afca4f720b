// The BVH finds exactly the overlapping boxes a brute-force scan finds, deterministically.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "solver/contact/bvh.hpp"

namespace grip::solver {
namespace {

std::vector<Aabb> random_boxes(int count, double extent, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> position(0.0, 1.0);
  std::uniform_real_distribution<double> size(0.0, extent);
  std::vector<Aabb> boxes(count);
  for (auto& box : boxes) {
    const Eigen::Vector3d corner(position(rng), position(rng), position(rng));
    box.expand(corner);
    box.expand(corner + Eigen::Vector3d(size(rng), size(rng), size(rng)));
  }
  return boxes;
}

TEST(Bvh, FindsExactlyTheOverlapsBruteForceFinds) {
  for (const int count : {0, 1, 3, 4, 5, 17, 1000}) {
    const auto boxes = random_boxes(count, 0.08, 7 + count);
    Bvh bvh;
    bvh.build(boxes);
    for (const auto& query : random_boxes(50, 0.2, 99)) {
      std::vector<int> found;
      bvh.query(query, [&](int i) { found.push_back(i); });
      std::vector<int> expected;
      for (int i = 0; i < count; ++i) {
        if (boxes[i].overlaps(query)) expected.push_back(i);
      }
      std::sort(found.begin(), found.end());
      EXPECT_EQ(found, expected) << count << " boxes";
    }
  }
}

TEST(Bvh, DegenerateAndCoincidentBoxes) {
  // Points (zero-size boxes) all at one place: every query touching it finds all of them.
  std::vector<Aabb> boxes(40);
  for (auto& box : boxes) box.expand(Eigen::Vector3d(0.5, 0.5, 0.5));
  Bvh bvh;
  bvh.build(boxes);
  Aabb touching;
  touching.expand(Eigen::Vector3d(0.5, 0.5, 0.5));
  touching.expand(Eigen::Vector3d(0.6, 0.6, 0.6));
  int hits = 0;
  bvh.query(touching, [&](int) { ++hits; });
  EXPECT_EQ(hits, 40);
  Aabb apart;
  apart.expand(Eigen::Vector3d(0.51, 0.5, 0.5));
  apart.expand(Eigen::Vector3d(0.6, 0.6, 0.6));
  hits = 0;
  bvh.query(apart, [&](int) { ++hits; });
  EXPECT_EQ(hits, 0);
}

TEST(Bvh, QueryOrderIsDeterministic) {
  const auto boxes = random_boxes(500, 0.1, 3);
  Bvh a;
  Bvh b;
  a.build(boxes);
  b.build(boxes);
  const auto query = random_boxes(1, 0.5, 4).front();
  std::vector<int> from_a;
  std::vector<int> from_b;
  a.query(query, [&](int i) { from_a.push_back(i); });
  b.query(query, [&](int i) { from_b.push_back(i); });
  EXPECT_FALSE(from_a.empty());
  EXPECT_EQ(from_a, from_b);
}

TEST(Aabb, InflateMakesNearBoxesOverlap) {
  Aabb a;
  a.expand(Eigen::Vector3d::Zero());
  Aabb b;
  b.expand(Eigen::Vector3d(1e-3 + 1e-9, 0, 0));
  EXPECT_FALSE(a.overlaps(b));
  a.inflate(0.5e-3);
  b.inflate(0.5e-3);
  EXPECT_FALSE(a.overlaps(b));
  a.inflate(1e-9);
  EXPECT_TRUE(a.overlaps(b));
}

}  // namespace
}  // namespace grip::solver
