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
  if (matrix_.rows() != n || fixed_ != fixed) {
    fixed_ = fixed;
    positions_.clear();
    build_pattern(n, triplets, false);
  }
  // Each triplet's slot: the last assembly's at the same index if the position repeats, else
  // looked up; a position the pattern lacks grows it.
  positions_.resize(triplets.size(), -1);
  slot_.resize(triplets.size());
  for (std::size_t i = 0; i < triplets.size(); ++i) {
    const long long position = key(n, triplets[i]);
    if (positions_[i] == position) continue;
    positions_[i] = position;
    slot_[i] = triplet_slot(triplets[i]);
    if (slot_[i] == kNotInPattern) {
      const bool grow = matrix_.nonZeros() <= fresh_nonzeros_ + fresh_nonzeros_ / 5;
      build_pattern(n, triplets, grow);
      for (std::size_t j = 0; j < triplets.size(); ++j) {
        positions_[j] = key(n, triplets[j]);
        slot_[j] = triplet_slot(triplets[j]);
      }
      break;
    }
  }
  // Sums in the triplets' order, as setFromTriplets does.
  double* values = matrix_.valuePtr();
  std::fill(values, values + matrix_.nonZeros(), 0.0);
  for (std::size_t i = 0; i < triplets.size(); ++i) {
    if (slot_[i] >= 0) values[slot_[i]] += triplets[i].value();
  }
  for (const int s : unit_slots_) values[s] = 1.0;
  return matrix_;
}

void SparseAssembly::build_pattern(int n, const std::vector<Eigen::Triplet<double>>& triplets,
                                   bool grow) {
  // Scratch, freed on return: a pattern is built rarely (the first iterations of a scene, and when
  // contacts add entries), and kept it would cost as much memory as the triplets, per environment.
  std::vector<Eigen::Triplet<double>> pattern;
  if (grow) {
    for (int col = 0; col < matrix_.outerSize(); ++col) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(matrix_, col); it; ++it) {
        pattern.emplace_back(static_cast<int>(it.row()), col, 0.0);
      }
    }
  }
  for (const auto& t : triplets) {
    if (!is_fixed(t.row()) && !is_fixed(t.col())) pattern.emplace_back(t.row(), t.col(), 0.0);
  }
  for (int i = 0; i < n; ++i) {
    if (is_fixed(i)) pattern.emplace_back(i, i, 0.0);
  }
  matrix_.resize(n, n);
  matrix_.setFromTriplets(pattern.begin(), pattern.end());
  matrix_.makeCompressed();
  if (!grow) fresh_nonzeros_ = matrix_.nonZeros();
  unit_slots_.clear();
  for (int i = 0; i < n; ++i) {
    if (is_fixed(i)) unit_slots_.push_back(slot(i, i));
  }
  ++pattern_builds_;
}

int SparseAssembly::slot(int row, int col) const {
  // A binary search among the column's rows.
  const int* rows = matrix_.innerIndexPtr();
  const int* begin = rows + matrix_.outerIndexPtr()[col];
  const int* end = rows + matrix_.outerIndexPtr()[col + 1];
  const int* found = std::lower_bound(begin, end, row);
  return found != end && *found == row ? static_cast<int>(found - rows) : kNotInPattern;
}

int SparseAssembly::triplet_slot(const Eigen::Triplet<double>& t) const {
  return is_fixed(t.row()) || is_fixed(t.col()) ? kLeftOut : slot(t.row(), t.col());
}

}  // namespace grip::solver
