#pragma once
// Sparse symmetric positive-definite solves for one environment's Newton systems, by CHOLMOD.
// The symbolic analysis (supernodal structure for a fill-reducing ordering) is done once per
// sparsity pattern and reused by every numeric factorization with that pattern.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <string>
#include <vector>

#include "solver/linear/linear_system_solver.hpp"

namespace grip::solver {

class SparseCholesky : public LinearSystemSolver {
 public:
  // CHOLMOD computes the ordering at each analysis: METIS (nested dissection) suits the large
  // FEM systems of soft fingers and objects; AMD is cheaper to compute for small or very
  // sparse systems.
  enum class Ordering { kMetis, kAmd };

  explicit SparseCholesky(Ordering ordering = Ordering::kMetis);
  // Every analysis uses this permutation (new-to-old, as CHOLMOD's UserPerm) instead of
  // computing one: environments of one model share the ordering of its contact-free pattern
  // (Model::ordering), and a changed contact pattern then costs only the symbolic
  // factorization, not a new METIS call.
  explicit SparseCholesky(std::shared_ptr<const std::vector<int>> permutation);
  ~SparseCholesky();
  SparseCholesky(SparseCholesky&&) noexcept;
  SparseCholesky& operator=(SparseCholesky&&) noexcept;

  // Factorizes the symmetric matrix whose lower triangle (column-major, compressed) is given.
  // Re-analyses only when the pattern differs from the last one. Returns false when the
  // matrix is not numerically positive definite (solve() must then not be called).
  bool factorize(const Eigen::SparseMatrix<double>& lower) override;

  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const;
  // solve() as CG's preconditioner applies it, several times per factorization. Where the
  // factor's supernodes are small (preconditions_on_simplicial_copy()), on a copy of the factor
  // in simplicial form, made at the first call after a factorization and kept until the next: a
  // supernodal solve calls BLAS twice per supernode, and OpenBLAS takes and releases a lock on
  // every call, which small supernodes do not repay; the simplicial solve is the same arithmetic
  // without BLAS, and agrees with solve() to round-off. Large supernodes are solved faster by
  // BLAS, so there the supernodal factor is used. The copy costs the factor's size again.
  Eigen::VectorXd precondition(const Eigen::VectorXd& rhs) const;
  // Whether precondition() uses the simplicial copy: a supernodal factor whose supernodes hold
  // fewer than kSmallSupernodeEntries entries on average. Measured (docs/simulation.md, item 3):
  // a fin-ray finger's, about 300, solves about 20 % faster on the copy; with a soft object's
  // tets, 800-2,900, 1.5-2.4x slower.
  bool preconditions_on_simplicial_copy() const;
  static constexpr std::size_t kSmallSupernodeEntries = 512;
  // The LinearSystemSolver form of solve(): never fails after a successful factorize().
  bool solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& x) override;
  // Solves lower x = rhs (symmetric positive definite, lower triangle as for factorize()) by
  // Eigen's conjugate gradients preconditioned with the last successful factorization, of an
  // earlier, nearby matrix: to a relative residual |lower x - rhs| / |rhs| of `tolerance` within
  // `max_iterations`. False (x unspecified) when there is no such factorization of this size or
  // CG did not get there; `iterations` says how many it took (products with `lower`). The
  // factorization is kept.
  bool solve_preconditioned(const Eigen::SparseMatrix<double>& lower, const Eigen::VectorXd& rhs,
                            double tolerance, int max_iterations, Eigen::VectorXd& x,
                            int& iterations) const;
  std::string failure() const override { return "the matrix is not positive definite"; }
  bool refuses_indefinite() const override { return true; }

  // Symbolic analyses done so far: one per distinct pattern seen in a row.
  int analyses() const;
  // The most memory CHOLMOD held at once for this solver so far (factor and workspace), bytes.
  std::size_t peak_bytes() const;
  // The last factor's numeric values: entries, and bytes (0 before the first factorize()).
  std::size_t factor_entries() const;
  std::size_t factor_bytes() const;
  // The floating-point operations of one numeric factorization, by the last analysis.
  double factor_flops() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The numeric values of the Cholesky factor of an n x n symmetric pattern (its lower triangle,
// compressed by columns: outer, inner) under `permutation` (new-to-old), bytes, as
// SparseCholesky would allocate them: from CHOLMOD's symbolic analysis alone, with no numeric
// work, so a caller can tell before factorizing whether the factor fits its memory.
std::size_t symbolic_factor_bytes(int n, const std::vector<int>& outer,
                                  const std::vector<int>& inner,
                                  const std::vector<int>& permutation);

}  // namespace grip::solver
