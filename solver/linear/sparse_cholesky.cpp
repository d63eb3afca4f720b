#include "solver/linear/sparse_cholesky.hpp"

#include "solver/linear/blas_threads.hpp"

#include <cholmod.h>
#include <Eigen/IterativeLinearSolvers>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace grip::solver {

namespace {

// A CHOLMOD view of Eigen's compressed lower triangle (no copy).
cholmod_sparse view_lower(const Eigen::SparseMatrix<double>& m) {
  cholmod_sparse a{};
  a.nrow = static_cast<std::size_t>(m.rows());
  a.ncol = static_cast<std::size_t>(m.cols());
  a.nzmax = static_cast<std::size_t>(m.nonZeros());
  a.p = const_cast<int*>(m.outerIndexPtr());
  a.i = const_cast<int*>(m.innerIndexPtr());
  a.x = const_cast<double*>(m.valuePtr());
  a.stype = -1;  // symmetric, lower triangle stored
  a.itype = CHOLMOD_INT;
  a.xtype = CHOLMOD_REAL;
  a.dtype = CHOLMOD_DOUBLE;
  a.sorted = 1;
  a.packed = 1;
  return a;
}

// The settings every analysis and factorization here shares.
void configure(cholmod_common& common, int ordering) {
  common.nmethods = 1;  // exactly the ordering asked for, not CHOLMOD's try-several default
  common.method[0].ordering = ordering;
  common.supernodal = CHOLMOD_AUTO;  // supernodal or simplicial by flop count
  // LL' also in the simplicial case: LDL' would "succeed" on an indefinite matrix.
  common.final_ll = 1;
  // Silent: factorize() reports a matrix that is not positive definite (Newton then projects
  // its contact Hessians and tries again), and CHOLMOD would print it as an error.
  common.print = 0;
}

// Entries of L's numeric values: a supernodal factor's are allocated by the analysis (xsize);
// a simplicial one's are its columns' counts of nonzeros (without the slack CHOLMOD allocates
// for growth).
std::size_t entries_of(const cholmod_factor& factor) {
  if (factor.is_super) return factor.xsize;
  const int* counts = static_cast<const int*>(factor.ColCount);
  std::size_t entries = 0;
  for (std::size_t j = 0; j < factor.n; ++j) entries += static_cast<std::size_t>(counts[j]);
  return entries;
}

// x = A^-1 rhs by CHOLMOD's solve with `factor`.
Eigen::VectorXd solve_with(cholmod_factor* factor, const Eigen::VectorXd& rhs,
                           cholmod_common& common) {
  cholmod_dense b{};
  b.nrow = static_cast<std::size_t>(rhs.size());
  b.ncol = 1;
  b.nzmax = b.nrow;
  b.d = b.nrow;
  b.x = const_cast<double*>(rhs.data());
  b.xtype = CHOLMOD_REAL;
  b.dtype = CHOLMOD_DOUBLE;
  cholmod_dense* x = cholmod_solve(CHOLMOD_A, factor, &b, &common);
  if (x == nullptr) throw std::runtime_error("CHOLMOD solve failed");
  Eigen::VectorXd result =
      Eigen::Map<const Eigen::VectorXd>(static_cast<double*>(x->x), rhs.size());
  cholmod_free_dense(&x, &common);
  return result;
}

}  // namespace

struct SparseCholesky::Impl {
  cholmod_common common{};
  cholmod_factor* factor = nullptr;
  cholmod_factor* simplicial = nullptr;  // precondition()'s copy of `factor`, once made
  std::shared_ptr<const std::vector<int>> permutation;  // empty: CHOLMOD orders
  std::vector<int> outer;                               // the analysed pattern, to detect a change
  std::vector<int> inner;
  int analyses = 0;
  bool factorized = false;  // the factor holds the last factorize()'s matrix, which succeeded

  Impl() { cholmod_start(&common); }
  ~Impl() {
    if (factor != nullptr) cholmod_free_factor(&factor, &common);
    if (simplicial != nullptr) cholmod_free_factor(&simplicial, &common);
    cholmod_finish(&common);
  }

  bool same_pattern(const Eigen::SparseMatrix<double>& m) const {
    return factor != nullptr && m.outerSize() + 1 == static_cast<Eigen::Index>(outer.size()) &&
           std::equal(outer.begin(), outer.end(), m.outerIndexPtr()) &&
           std::equal(inner.begin(), inner.end(), m.innerIndexPtr());
  }
};

SparseCholesky::SparseCholesky(Ordering ordering) : impl_(std::make_unique<Impl>()) {
  configure(impl_->common, ordering == Ordering::kMetis ? CHOLMOD_METIS : CHOLMOD_AMD);
}

SparseCholesky::SparseCholesky(std::shared_ptr<const std::vector<int>> permutation)
    : SparseCholesky(Ordering::kMetis) {
  if (!permutation) throw std::invalid_argument("SparseCholesky: null permutation");
  impl_->permutation = std::move(permutation);
  impl_->common.method[0].ordering = CHOLMOD_GIVEN;
}

SparseCholesky::~SparseCholesky() = default;
SparseCholesky::SparseCholesky(SparseCholesky&&) noexcept = default;
SparseCholesky& SparseCholesky::operator=(SparseCholesky&&) noexcept = default;

bool SparseCholesky::factorize(const Eigen::SparseMatrix<double>& lower) {
  if (!lower.isCompressed()) {
    throw std::invalid_argument("SparseCholesky::factorize needs a compressed matrix");
  }
  Impl& impl = *impl_;
  cholmod_sparse a = view_lower(lower);
  if (!impl.same_pattern(lower)) {
    if (impl.factor != nullptr) cholmod_free_factor(&impl.factor, &impl.common);
    int* perm = nullptr;
    if (impl.permutation) {
      if (impl.permutation->size() != static_cast<std::size_t>(lower.rows())) {
        throw std::invalid_argument(
            "SparseCholesky: the permutation has " + std::to_string(impl.permutation->size()) +
            " entries for a matrix of size " + std::to_string(lower.rows()));
      }
      perm = const_cast<int*>(impl.permutation->data());
    }
    impl.factor = cholmod_analyze_p(&a, perm, nullptr, 0, &impl.common);
    if (impl.factor == nullptr) throw std::runtime_error("CHOLMOD analysis failed");
    impl.outer.assign(lower.outerIndexPtr(), lower.outerIndexPtr() + lower.outerSize() + 1);
    impl.inner.assign(lower.innerIndexPtr(), lower.innerIndexPtr() + lower.nonZeros());
    ++impl.analyses;
  }
  use_single_threaded_openmp();
  cholmod_factorize(&a, impl.factor, &impl.common);
  impl.factorized = impl.common.status == CHOLMOD_OK && impl.factor->minor == impl.factor->n;
  if (impl.simplicial != nullptr) cholmod_free_factor(&impl.simplicial, &impl.common);
  return impl.factorized;
}

Eigen::VectorXd SparseCholesky::solve(const Eigen::VectorXd& rhs) const {
  return solve_with(impl_->factor, rhs, impl_->common);
}

bool SparseCholesky::preconditions_on_simplicial_copy() const {
  const cholmod_factor* factor = impl_->factor;
  return factor != nullptr && factor->is_super &&
         factor->xsize < kSmallSupernodeEntries * factor->nsuper;
}

Eigen::VectorXd SparseCholesky::precondition(const Eigen::VectorXd& rhs) const {
  Impl& impl = *impl_;
  if (!preconditions_on_simplicial_copy()) return solve(rhs);
  if (impl.simplicial == nullptr) {
    impl.simplicial = cholmod_copy_factor(impl.factor, &impl.common);
    // LL', simplicial, packed, monotonic: the supernodal factor's numbers, column by column.
    if (impl.simplicial == nullptr ||
        !cholmod_change_factor(CHOLMOD_REAL, 1, 0, 1, 1, impl.simplicial, &impl.common)) {
      // No half-made copy is left for a later call to solve with.
      if (impl.simplicial != nullptr) cholmod_free_factor(&impl.simplicial, &impl.common);
      throw std::runtime_error("CHOLMOD could not copy the factor to simplicial form");
    }
  }
  return solve_with(impl.simplicial, rhs, impl.common);
}

bool SparseCholesky::solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& x) {
  x = static_cast<const SparseCholesky&>(*this).solve(rhs);
  return true;
}

namespace {

// Eigen's preconditioner interface over a SparseCholesky's factor of another matrix.
class FactorPreconditioner {
 public:
  FactorPreconditioner() = default;
  void use(const SparseCholesky& factor) { factor_ = &factor; }
  template <typename Matrix>
  FactorPreconditioner& analyzePattern(const Matrix&) {
    return *this;
  }
  template <typename Matrix>
  FactorPreconditioner& factorize(const Matrix&) {
    return *this;
  }
  template <typename Matrix>
  FactorPreconditioner& compute(const Matrix&) {
    return *this;
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& r) const { return factor_->precondition(r); }
  Eigen::ComputationInfo info() const { return Eigen::Success; }

 private:
  const SparseCholesky* factor_ = nullptr;
};

}  // namespace

bool SparseCholesky::solve_preconditioned(const Eigen::SparseMatrix<double>& lower,
                                          const Eigen::VectorXd& rhs, double tolerance,
                                          int max_iterations, Eigen::VectorXd& x,
                                          int& iterations) const {
  iterations = 0;
  if (!impl_->factorized || impl_->factor->n != static_cast<std::size_t>(lower.rows())) {
    return false;
  }
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower, FactorPreconditioner> cg;
  cg.preconditioner().use(*this);
  cg.setTolerance(tolerance);
  cg.setMaxIterations(max_iterations);
  cg.compute(lower);
  x = cg.solve(rhs);
  // Eigen counts the iterations before the one that got there; this counts products with the
  // matrix, that one included (none for a zero right-hand side).
  const bool converged = cg.info() == Eigen::Success;
  iterations = static_cast<int>(cg.iterations()) + (converged && rhs.squaredNorm() > 0.0 ? 1 : 0);
  return converged;
}

int SparseCholesky::analyses() const { return impl_->analyses; }

std::size_t SparseCholesky::peak_bytes() const { return impl_->common.memory_usage; }

std::size_t SparseCholesky::factor_entries() const {
  return impl_->factor == nullptr ? 0 : entries_of(*impl_->factor);
}

std::size_t SparseCholesky::factor_bytes() const { return factor_entries() * sizeof(double); }

double SparseCholesky::factor_flops() const { return impl_->common.fl; }

std::size_t symbolic_factor_bytes(int n, const std::vector<int>& outer,
                                  const std::vector<int>& inner,
                                  const std::vector<int>& permutation) {
  if (outer.size() != static_cast<std::size_t>(n) + 1 ||
      permutation.size() != static_cast<std::size_t>(n) ||
      inner.size() != static_cast<std::size_t>(outer.back())) {
    throw std::invalid_argument("symbolic_factor_bytes: inconsistent pattern or permutation");
  }
  cholmod_common common{};
  cholmod_start(&common);
  configure(common, CHOLMOD_GIVEN);
  cholmod_sparse a{};
  a.nrow = a.ncol = static_cast<std::size_t>(n);
  a.nzmax = inner.size();
  a.p = const_cast<int*>(outer.data());
  a.i = const_cast<int*>(inner.data());
  a.stype = -1;
  a.itype = CHOLMOD_INT;
  a.xtype = CHOLMOD_PATTERN;
  a.dtype = CHOLMOD_DOUBLE;
  a.sorted = 1;
  a.packed = 1;
  cholmod_factor* factor =
      cholmod_analyze_p(&a, const_cast<int*>(permutation.data()), nullptr, 0, &common);
  if (factor == nullptr) {
    cholmod_finish(&common);
    throw std::runtime_error("CHOLMOD analysis failed");
  }
  const std::size_t bytes = entries_of(*factor) * sizeof(double);
  cholmod_free_factor(&factor, &common);
  cholmod_finish(&common);
  return bytes;
}

}  // namespace grip::solver
