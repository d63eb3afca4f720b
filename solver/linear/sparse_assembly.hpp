#pragma once
// Assembles a sparse matrix from triplets, reusing the sparsity pattern while the triplets'
// positions repeat from one Newton iteration to the next (the same elements and contacts):
// then only the values are summed in place, with no sorting and no allocation.
#include <Eigen/SparseCore>
#include <vector>

namespace grip::solver {

class SparseAssembly {
 public:
  // The matrix of `triplets` (duplicates summed), size n x n, compressed.
  const Eigen::SparseMatrix<double>& assemble(int n,
                                              const std::vector<Eigen::Triplet<double>>& triplets);

  // How many times the pattern was built from scratch.
  int pattern_builds() const { return pattern_builds_; }

 private:
  Eigen::SparseMatrix<double> matrix_;
  std::vector<long long> positions_;  // the triplets' (row, col) keys of the current pattern
  std::vector<int> slot_;             // each triplet's index into the matrix's values
  int pattern_builds_ = 0;
};

}  // namespace grip::solver
