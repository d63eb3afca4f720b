// METIS row partitions: contiguous ranges per part, whole vertex blocks, few cut couplings.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "farm/petsc/row_partition.hpp"

namespace grip::farm {
namespace {

// The lower triangle of a 3D grid Laplacian with 3 rows per vertex (dense 3x3 blocks).
Eigen::SparseMatrix<double> grid_matrix(int side) {
  auto vertex = [side](int i, int j, int k) { return (k * side + j) * side + i; };
  std::vector<Eigen::Triplet<double>> entries;
  auto couple = [&](int a, int b, double value) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) {
        if (3 * a + r >= 3 * b + c) entries.emplace_back(3 * a + r, 3 * b + c, value);
      }
  };
  for (int k = 0; k < side; ++k)
    for (int j = 0; j < side; ++j)
      for (int i = 0; i < side; ++i) {
        const int v = vertex(i, j, k);
        couple(v, v, 6.0);
        if (i > 0) couple(v, vertex(i - 1, j, k), -1.0);
        if (j > 0) couple(v, vertex(i, j - 1, k), -1.0);
        if (k > 0) couple(v, vertex(i, j, k - 1), -1.0);
      }
  const int n = 3 * side * side * side;
  Eigen::SparseMatrix<double> lower(n, n);
  lower.setFromTriplets(entries.begin(), entries.end());
  lower.makeCompressed();
  return lower;
}

TEST(RowPartition, OneRangePerPartOfWholeBlocksWithFewCutCouplings) {
  const int side = 12;
  const Eigen::SparseMatrix<double> lower = grid_matrix(side);
  const int n = static_cast<int>(lower.rows());
  for (const int parts : {1, 2, 3, 4}) {
    const RowPartition partition = partition_rows(lower, parts, 3);
    ASSERT_EQ(partition.row_begin.size(), static_cast<std::size_t>(parts + 1));
    EXPECT_EQ(partition.row_begin.front(), 0);
    EXPECT_EQ(partition.row_begin.back(), n);
    // A permutation that keeps each vertex's three rows together and in order.
    std::vector<int> sorted = partition.new_of_old;
    std::sort(sorted.begin(), sorted.end());
    for (int i = 0; i < n; ++i) ASSERT_EQ(sorted[i], i);
    for (int v = 0; v < n / 3; ++v) {
      EXPECT_EQ(partition.new_of_old[3 * v] % 3, 0);
      EXPECT_EQ(partition.new_of_old[3 * v + 1], partition.new_of_old[3 * v] + 1);
      EXPECT_EQ(partition.new_of_old[3 * v + 2], partition.new_of_old[3 * v] + 2);
    }
    // Balanced within METIS's default 3% imbalance (plus a block of rounding).
    for (int p = 0; p < parts; ++p) {
      const int size = partition.row_begin[p + 1] - partition.row_begin[p];
      EXPECT_LE(size, 1.03 * n / parts + 3) << parts << " parts";
    }
    // A good cut: far fewer vertex couplings cross parts than a slab split of the grid's
    // index order would cut for 2 parts (one full plane, side^2 couplings), per part boundary.
    auto part_of = [&](int row) {
      const int r = partition.new_of_old[row];
      return static_cast<int>(
                 std::upper_bound(partition.row_begin.begin(), partition.row_begin.end(), r) -
                 partition.row_begin.begin()) -
             1;
    };
    int cut = 0;
    for (int c = 0; c < n; c += 3) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(lower, c); it; ++it) {
        if (it.row() % 3 == 0 && it.row() != c && part_of(it.row()) != part_of(c)) ++cut;
      }
    }
    if (parts == 1) {
      EXPECT_EQ(cut, 0);
    }
    EXPECT_LE(cut, (parts - 1) * side * side * 3 / 2) << parts << " parts";
  }
}

TEST(RowPartition, RejectsRowsThatDoNotFillBlocks) {
  Eigen::SparseMatrix<double> lower(4, 4);
  lower.setIdentity();
  lower.makeCompressed();
  EXPECT_THROW(partition_rows(lower, 2, 3), std::invalid_argument);
}

}  // namespace
}  // namespace grip::farm
