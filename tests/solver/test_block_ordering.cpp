// The block nested-dissection ordering: a permutation that keeps blocks whole, eliminates a
// hub last (no fill), and serves CHOLMOD as a given ordering with correct solves.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "solver/linear/block_ordering.hpp"
#include "solver/linear/sparse_cholesky.hpp"

namespace grip::solver {
namespace {

// A star of `leaves` 3-DOF blocks around one hub block (block 0).
BlockGraph star(int leaves) {
  BlockGraph graph;
  for (int b = 0; b <= leaves; ++b) graph.block_offset.push_back(3 * b);
  graph.block_offset.push_back(3 * (leaves + 1));
  graph.neighbours.resize(leaves + 1);
  for (int leaf = 1; leaf <= leaves; ++leaf) {
    graph.neighbours[0].push_back(leaf);
    graph.neighbours[leaf].push_back(0);
  }
  return graph;
}

TEST(BlockOrdering, IsAPermutationThatKeepsBlocksWhole) {
  const BlockGraph graph = star(20);
  const std::vector<int> order = nested_dissection_ordering(graph);
  ASSERT_EQ(order.size(), 63u);
  std::vector<int> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  std::vector<int> identity(order.size());
  std::iota(identity.begin(), identity.end(), 0);
  EXPECT_EQ(sorted, identity);
  for (std::size_t k = 0; k < order.size(); k += 3) {
    EXPECT_EQ(order[k] % 3, 0);
    EXPECT_EQ(order[k + 1], order[k] + 1);
    EXPECT_EQ(order[k + 2], order[k] + 2);
  }
}

TEST(BlockOrdering, EliminatesTheHubOfAStarLast) {
  // Eliminating the hub first would couple every leaf with every other (full fill); the
  // new-to-old order must put the hub's DOFs at the end.
  const std::vector<int> order = nested_dissection_ordering(star(20));
  EXPECT_EQ(order[order.size() - 3], 0);
}

TEST(BlockOrdering, GivenToCholmodSolvesCorrectly) {
  const int leaves = 30;
  const BlockGraph graph = star(leaves);
  const int n = graph.block_offset.back();
  // An SPD matrix with the star's block pattern: diagonally dominant.
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::vector<Eigen::Triplet<double>> entries;
  for (int d = 0; d < n; ++d) entries.emplace_back(d, d, 3.0 * leaves + 10.0);
  for (int leaf = 1; leaf <= leaves; ++leaf) {
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) entries.emplace_back(3 * leaf + i, j, uniform(rng));
    }
  }
  Eigen::SparseMatrix<double> lower(n, n);
  lower.setFromTriplets(entries.begin(), entries.end());
  lower.makeCompressed();
  Eigen::VectorXd b(n);
  for (int d = 0; d < n; ++d) b[d] = uniform(rng);

  SparseCholesky given(std::make_shared<const std::vector<int>>(nested_dissection_ordering(graph)));
  SparseCholesky metis(SparseCholesky::Ordering::kMetis);
  ASSERT_TRUE(given.factorize(lower));
  ASSERT_TRUE(metis.factorize(lower));
  const Eigen::VectorXd x = given.solve(b);
  const Eigen::VectorXd residual = lower.selfadjointView<Eigen::Lower>() * x - b;
  EXPECT_LT(residual.norm() / b.norm(), 1e-12);
  EXPECT_LT((x - metis.solve(b)).norm() / x.norm(), 1e-12);

  // A permutation of the wrong size is refused, not silently misused.
  SparseCholesky wrong(std::make_shared<const std::vector<int>>(std::vector<int>{0, 1, 2}));
  EXPECT_THROW(wrong.factorize(lower), std::invalid_argument);
}

}  // namespace
}  // namespace grip::solver
