#include "solver/linear/sparse_assembly.hpp"

#include <algorithm>

namespace grip::solver {
namespace {

long long key(int n, const Eigen::Triplet<double>& t) {
  return static_cast<long long>(t.col()) * n + t.row();
}

}  // namespace

const Eigen::SparseMatrix<double>& SparseAssembly::assemble(
    int n, const std::vector<Eigen::Triplet<double>>& triplets, const std::vector<char>& fixed) {
  if (matrix_.rows() != n || positions_.size() != triplets.size() || fixed_ != fixed) {
    return build(n, triplets, fixed);
  }
  double* values = matrix_.valuePtr();
  std::fill(values, values + matrix_.nonZeros(), 0.0);
  // Sums in the triplets' order, as setFromTriplets does; a position that moved means a new
  // pattern (a contact came or went).
  for (std::size_t i = 0; i < triplets.size(); ++i) {
    if (positions_[i] != key(n, triplets[i])) return build(n, triplets, fixed);
    if (slot_[i] >= 0) values[slot_[i]] += triplets[i].value();
  }
  for (const int s : unit_slots_) values[s] = 1.0;
  return matrix_;
}

const Eigen::SparseMatrix<double>& SparseAssembly::build(
    int n, const std::vector<Eigen::Triplet<double>>& triplets, const std::vector<char>& fixed) {
  const auto is_fixed = [&](int i) { return !fixed.empty() && fixed[i]; };
  kept_.clear();
  for (const auto& t : triplets) {
    if (!is_fixed(t.row()) && !is_fixed(t.col())) kept_.push_back(t);
  }
  for (int i = 0; i < n; ++i) {
    if (is_fixed(i)) kept_.emplace_back(i, i, 1.0);
  }
  matrix_.resize(n, n);
  matrix_.setFromTriplets(kept_.begin(), kept_.end());
  matrix_.makeCompressed();
  fixed_ = fixed;
  // An entry's index in the compressed column: a binary search among the column's rows.
  const auto slot = [&](int row, int col) {
    const int* rows = matrix_.innerIndexPtr();
    const int begin = matrix_.outerIndexPtr()[col];
    const int end = matrix_.outerIndexPtr()[col + 1];
    return static_cast<int>(std::lower_bound(rows + begin, rows + end, row) - rows);
  };
  positions_.resize(triplets.size());
  slot_.resize(triplets.size());
  for (std::size_t i = 0; i < triplets.size(); ++i) {
    const auto& t = triplets[i];
    positions_[i] = key(n, t);
    slot_[i] = is_fixed(t.row()) || is_fixed(t.col()) ? -1 : slot(t.row(), t.col());
  }
  unit_slots_.clear();
  for (int i = 0; i < n; ++i) {
    if (is_fixed(i)) unit_slots_.push_back(slot(i, i));
  }
  ++pattern_builds_;
  return matrix_;
}

}  // namespace grip::solver
