#pragma once
// A solver of Newton systems. Every environment has its own sparse Cholesky (CHOLMOD); another
// solver can take its place for big systems (Environment::use_linear_solver), e.g. an iterative
// solve across MPI ranks (farm/petsc).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>

namespace grip::solver {

class LinearSystemSolver {
 public:
  virtual ~LinearSystemSolver() = default;

  // Prepares solves with the symmetric positive-definite matrix whose lower triangle
  // (column-major, compressed) is given. False when it cannot; failure() then says why.
  virtual bool factorize(const Eigen::SparseMatrix<double>& lower) = 0;

  // Solves with the matrix of the last successful factorize(). False when no solution to the
  // solver's accuracy was found (x is then unspecified); failure() then says why.
  virtual bool solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& x) = 0;

  // Why the last factorize() or solve() failed.
  virtual std::string failure() const = 0;

  // True when factorize() refuses every matrix that is not positive definite (a Cholesky does;
  // an iterative solver may return a step for one). Newton gives exact, possibly indefinite
  // contact Hessians only to such a solver.
  virtual bool refuses_indefinite() const { return false; }
};

}  // namespace grip::solver
