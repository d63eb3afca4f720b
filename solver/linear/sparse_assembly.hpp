#pragma once
// Assembles a sparse matrix from triplets, reusing the sparsity pattern while the triplets'
// positions repeat from one Newton iteration to the next (the same elements and contacts):
// then only the values are summed in place, with no sorting and no allocation.
#include <Eigen/SparseCore>
#include <vector>

namespace grip::solver {

class SparseAssembly {
 public:
  // The matrix of `triplets` (duplicates summed), size n x n, compressed. Rows and columns i
  // with fixed[i] set (prescribed DOFs) are left out and get a 1 on the diagonal instead; an
  // empty `fixed` fixes none. One pass over the triplets while the pattern repeats.
  const Eigen::SparseMatrix<double>& assemble(int n,
                                              const std::vector<Eigen::Triplet<double>>& triplets,
                                              const std::vector<char>& fixed = {});

  // How many times the pattern was built from scratch.
  int pattern_builds() const { return pattern_builds_; }

 private:
  const Eigen::SparseMatrix<double>& build(int n,
                                           const std::vector<Eigen::Triplet<double>>& triplets,
                                           const std::vector<char>& fixed);

  Eigen::SparseMatrix<double> matrix_;
  std::vector<char> fixed_;
  std::vector<long long> positions_;  // the triplets' (row, col) keys of the current pattern
  std::vector<int> slot_;             // each triplet's index into the matrix's values, or -1
  std::vector<int> unit_slots_;       // the fixed DOFs' diagonal entries
  std::vector<Eigen::Triplet<double>> kept_;  // scratch of build()
  int pattern_builds_ = 0;
};

}  // namespace grip::solver
