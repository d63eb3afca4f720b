#pragma once
// Assembles a sparse matrix from triplets, keeping its sparsity pattern from one Newton
// iteration to the next. The elements' entries repeat in place; a contact's entries come and go
// at the end of the list. An entry whose position is already in the pattern is summed in
// place; a new one grows the pattern, which keeps the entries of contacts that have gone as
// explicit zeros, so that a grasp's contacts, once seen, cost no new pattern (nor CHOLMOD a new
// symbolic analysis). A pattern grown by more than a fifth past its last fresh build is built
// fresh again.
#include <Eigen/SparseCore>
#include <vector>

namespace grip::solver {

class SparseAssembly {
 public:
  // The matrix of `triplets` (duplicates summed in the triplets' order), size n x n, compressed,
  // perhaps with explicit zeros. Rows and columns i with fixed[i] set (prescribed DOFs) are left
  // out and get a 1 on the diagonal instead; an empty `fixed` fixes none.
  const Eigen::SparseMatrix<double>& assemble(int n,
                                              const std::vector<Eigen::Triplet<double>>& triplets,
                                              const std::vector<char>& fixed = {});

  // How many times the pattern was built (fresh or grown).
  int pattern_builds() const { return pattern_builds_; }

 private:
  // The pattern of `triplets` (their free entries, the fixed DOFs' diagonals), with the current
  // pattern's entries too when `grow`.
  void build_pattern(int n, const std::vector<Eigen::Triplet<double>>& triplets, bool grow);
  static constexpr int kLeftOut = -1;       // a fixed DOF's row or column
  static constexpr int kNotInPattern = -2;  // a position the pattern lacks
  // The index of entry (row, col) in the matrix's values, or kNotInPattern.
  int slot(int row, int col) const;
  // A triplet's index into the matrix's values, kLeftOut or kNotInPattern.
  int triplet_slot(const Eigen::Triplet<double>& t) const;
  bool is_fixed(int i) const { return !fixed_.empty() && fixed_[i]; }

  Eigen::SparseMatrix<double> matrix_;
  std::vector<char> fixed_;
  std::vector<long long> positions_;  // the last triplets' (row, col) keys
  std::vector<int> slot_;             // each one's triplet_slot
  std::vector<int> unit_slots_;       // the fixed DOFs' diagonal entries
  long long fresh_nonzeros_ = 0;      // the pattern's size when it was last built fresh
  int pattern_builds_ = 0;
};

}  // namespace grip::solver
