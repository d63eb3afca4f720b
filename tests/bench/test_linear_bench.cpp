// The Newton systems `grip bench linear` times: a real bimanual soft trial's, taken at the first
// Newton iteration in which the fin-ray fingers touch the soft bar, and as the trial's own
// solver would see them (symmetric positive definite, the bar and all four fingers' DOFs).
#include <gtest/gtest.h>

#include "bench/linear/bimanual_trial_system.hpp"
#include "solver/linear/sparse_cholesky.hpp"
#include "src/scene/primitives.hpp"

namespace grip::bench {
namespace {

TEST(LinearBench, ABimanualTrialsSystemCouplesTheFingersToTheBar) {
  const double cell = 0.01;
  const NewtonSystem system = capture_bimanual_trial_system(cell);
  const long bar_dofs =
      3 * scene::box_tets(Eigen::Vector3d(0.40, 0.05, 0.04), cell).vertices.rows();
  EXPECT_GT(system.lower.rows(), bar_dofs);  // the fingers' FEM DOFs and the jaws' too
  ASSERT_EQ(system.rhs.size(), system.lower.rows());
  // The fingers start 1.5 d_hat away: the first contact comes after a few Newton iterations.
  EXPECT_GT(system.newton_iterations, 1);
  solver::SparseCholesky cholesky;
  ASSERT_TRUE(cholesky.factorize(system.lower));
  const Eigen::VectorXd x = cholesky.solve(system.rhs);
  const Eigen::VectorXd residual = system.lower.selfadjointView<Eigen::Lower>() * x - system.rhs;
  EXPECT_LT(residual.norm(), 1e-8 * system.rhs.norm());
  // Contact couples a finger's surface vertices to the bar's: off-diagonal blocks between two
  // bodies, which no single body's tets give. Bar DOFs come first (body 0).
  bool coupled = false;
  for (int col = 0; col < bar_dofs && !coupled; ++col) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(system.lower, col); it; ++it) {
      if (it.row() >= bar_dofs && it.value() != 0.0) coupled = true;
    }
  }
  EXPECT_TRUE(coupled);
}

}  // namespace
}  // namespace grip::bench
