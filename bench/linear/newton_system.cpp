#include "bench/linear/newton_system.hpp"

#include <memory>
#include <stdexcept>

#include "solver/environment.hpp"
#include "solver/linear/sparse_cholesky.hpp"

namespace grip::bench {

namespace {

// Solves by CHOLMOD, as the environment would, and keeps the last system.
class RecordingSolver final : public solver::LinearSystemSolver {
 public:
  bool factorize(const Eigen::SparseMatrix<double>& lower) override {
    last_.lower = lower;
    return cholesky_.factorize(lower);
  }
  bool solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& x) override {
    last_.rhs = rhs;
    x = cholesky_.solve(rhs);
    return true;
  }
  std::string failure() const override { return "the matrix is not positive definite"; }
  const NewtonSystem& last() const { return last_; }

 private:
  solver::SparseCholesky cholesky_;
  NewtonSystem last_;
};

}  // namespace

NewtonSystem capture_newton_system(const solver::SceneDescription& scene, int steps) {
  solver::Environment env(solver::Model::build(scene));
  auto recorder = std::make_shared<RecordingSolver>();
  env.use_linear_solver(recorder, 0);
  for (int s = 0; s < steps; ++s) {
    if (!env.step()) throw std::runtime_error("capture_newton_system: " + env.failure());
  }
  NewtonSystem system = recorder->last();
  system.newton_iterations = static_cast<int>(env.statistics().newton_iterations);
  return system;
}

}  // namespace grip::bench
