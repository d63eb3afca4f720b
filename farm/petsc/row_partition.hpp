#pragma once
// Splits the rows of a symmetric sparse matrix among the ranks of a communicator: METIS
// partitions the graph of its 3x3 blocks (one block per vertex), and the rows are renumbered
// so that each rank owns one contiguous range, as PETSc's parallel matrices want.
#include <Eigen/SparseCore>
#include <vector>

namespace grip::farm {

struct RowPartition {
  std::vector<int> new_of_old;  // the new number of each row
  std::vector<int> row_begin;   // part p owns new rows [row_begin[p], row_begin[p + 1])
};

// Partitions the rows of the matrix whose lower triangle is given into `parts` parts of about
// equal size with few couplings between them. Rows go in blocks of `block_size` (which must
// divide the matrix size), keep their order within a part, and a block never splits.
RowPartition partition_rows(const Eigen::SparseMatrix<double>& lower, int parts, int block_size);

}  // namespace grip::farm
