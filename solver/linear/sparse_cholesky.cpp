#include "solver/linear/sparse_cholesky.hpp"

#include <Eigen/CholmodSupport>
#include <algorithm>
#include <stdexcept>
#include <vector>

namespace grip::solver {

struct SparseCholesky::Impl {
  Eigen::CholmodDecomposition<Eigen::SparseMatrix<double>, Eigen::Lower> cholmod;
  std::vector<int> outer;  // the analysed pattern, to detect a change
  std::vector<int> inner;
  int analyses = 0;

  bool same_pattern(const Eigen::SparseMatrix<double>& m) const {
    return m.outerSize() + 1 == static_cast<Eigen::Index>(outer.size()) &&
           std::equal(outer.begin(), outer.end(), m.outerIndexPtr()) &&
           std::equal(inner.begin(), inner.end(), m.innerIndexPtr());
  }
};

SparseCholesky::SparseCholesky(Ordering ordering) : impl_(std::make_unique<Impl>()) {
  cholmod_common& common = impl_->cholmod.cholmod();
  common.nmethods = 1;  // exactly the ordering asked for, not CHOLMOD's try-several default
  common.method[0].ordering = ordering == Ordering::kMetis ? CHOLMOD_METIS : CHOLMOD_AMD;
  impl_->cholmod.setMode(Eigen::CholmodAuto);  // supernodal or simplicial by flop count
  // LL' also in the simplicial case: LDL' would "succeed" on an indefinite matrix.
  common.final_ll = 1;
  common.print = 1;  // errors only: a non-positive-definite matrix is reported by factorize()
}

SparseCholesky::~SparseCholesky() = default;
SparseCholesky::SparseCholesky(SparseCholesky&&) noexcept = default;
SparseCholesky& SparseCholesky::operator=(SparseCholesky&&) noexcept = default;

bool SparseCholesky::factorize(const Eigen::SparseMatrix<double>& lower) {
  if (!lower.isCompressed()) {
    throw std::invalid_argument("SparseCholesky::factorize needs a compressed matrix");
  }
  if (!impl_->same_pattern(lower)) {
    impl_->cholmod.analyzePattern(lower);
    impl_->outer.assign(lower.outerIndexPtr(), lower.outerIndexPtr() + lower.outerSize() + 1);
    impl_->inner.assign(lower.innerIndexPtr(), lower.innerIndexPtr() + lower.nonZeros());
    ++impl_->analyses;
  }
  impl_->cholmod.factorize(lower);
  return impl_->cholmod.info() == Eigen::Success;
}

Eigen::VectorXd SparseCholesky::solve(const Eigen::VectorXd& rhs) const {
  return impl_->cholmod.solve(rhs);
}

int SparseCholesky::analyses() const { return impl_->analyses; }

}  // namespace grip::solver
