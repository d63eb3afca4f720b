#include "solver/linear/sparse_assembly.hpp"

#include <algorithm>

namespace grip::solver {

const Eigen::SparseMatrix<double>& SparseAssembly::assemble(
    int n, const std::vector<Eigen::Triplet<double>>& triplets) {
  auto key = [n](const Eigen::Triplet<double>& t) {
    return static_cast<long long>(t.col()) * n + t.row();
  };
  bool same = matrix_.rows() == n && positions_.size() == triplets.size();
  for (std::size_t i = 0; same && i < triplets.size(); ++i)
    same = positions_[i] == key(triplets[i]);
  if (same) {
    double* values = matrix_.valuePtr();
    std::fill(values, values + matrix_.nonZeros(), 0.0);
    for (std::size_t i = 0; i < triplets.size(); ++i) values[slot_[i]] += triplets[i].value();
    return matrix_;
  }
  matrix_.resize(n, n);
  matrix_.setFromTriplets(triplets.begin(), triplets.end());
  matrix_.makeCompressed();
  positions_.resize(triplets.size());
  slot_.resize(triplets.size());
  for (std::size_t i = 0; i < triplets.size(); ++i) {
    positions_[i] = key(triplets[i]);
    // The entry's index in the compressed column: a binary search among the column's rows.
    const int* rows = matrix_.innerIndexPtr();
    const int begin = matrix_.outerIndexPtr()[triplets[i].col()];
    const int end = matrix_.outerIndexPtr()[triplets[i].col() + 1];
    slot_[i] =
        static_cast<int>(std::lower_bound(rows + begin, rows + end, triplets[i].row()) - rows);
  }
  ++pattern_builds_;
  return matrix_;
}

}  // namespace grip::solver
