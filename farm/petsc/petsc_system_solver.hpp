#pragma once
// Newton systems solved by a PETSc Krylov solver (KSP) across the ranks of an MPI communicator.
// Rank 0 holds the matrix and is the environment's LinearSystemSolver; the other ranks serve(),
// each assembling and solving its METIS-chosen share of the rows in every factorize and solve.
#include <mpi.h>

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "solver/linear/linear_system_solver.hpp"

namespace grip::farm {

class PetscSystemSolver final : public solver::LinearSystemSolver {
 public:
  // grip's defaults, chosen by measurement (docs/linear-solvers.md): CG preconditioned by
  // smoothed-aggregation multigrid with SOR smoothing (which, unlike GAMG's default Chebyshev,
  // needs no eigenvalue estimate: those failed on stiff contact systems), stopping at
  // ||b - A x|| <= 1e-10 ||b|| on the true residual, far below what moves Newton's convergence
  // tests. Written into PETSc's options database under the solver's prefix where the database
  // has no value yet, so each one, and every other KSP or PC option, can be overridden there
  // (e.g. grip ... -- -ksp_type cg -pc_type bjacobi).
  static const std::vector<std::pair<std::string, std::string>>& default_options();

  // Collective over `comm`: every rank of it constructs its solver at the same time, with
  // PETSc initialized (PetscSession). The KSP reads its options under `options_prefix`
  // (e.g. "grip_" reads -grip_ksp_type); empty: plain -ksp_type.
  explicit PetscSystemSolver(MPI_Comm comm, const std::string& options_prefix = "");
  ~PetscSystemSolver() override;  // rank 0: stop()
  PetscSystemSolver(const PetscSystemSolver&) = delete;
  PetscSystemSolver& operator=(const PetscSystemSolver&) = delete;

  // Rank 0 only. factorize() distributes the matrix and sets up the preconditioner; solve()
  // runs the KSP and fails unless it converged.
  bool factorize(const Eigen::SparseMatrix<double>& lower) override;
  bool solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& x) override;
  std::string failure() const override;

  // Ranks other than 0: take part in every factorize and solve until rank 0 stops.
  void serve();
  // Rank 0: ends the other ranks' serve() and frees the PETSc objects on every rank.
  void stop();

  int rank() const;
  int ranks() const;
  // Krylov iterations of the last solve.
  int iterations() const;
  // Rank 0: systems solved so far.
  std::uint64_t solves() const;
  // The KSP and preconditioner in use, e.g. "cg + gamg/sor" or "cg + bjacobi/icc".
  std::string method() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace grip::farm
