// CHOLMOD solves: correct answers, one symbolic analysis per pattern, honest failure on
// matrices that are not positive definite.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "solver/linear/sparse_cholesky.hpp"

namespace grip::solver {
namespace {

// Lower triangle of a 3D grid Laplacian (7-point stencil) times `scale` plus `shift` * I:
// symmetric positive definite for shift > 0, with the fill pattern of a tet-mesh system.
Eigen::SparseMatrix<double> grid_system(int n, double scale, double shift) {
  const int size = n * n * n;
  auto id = [n](int i, int j, int k) { return (i * n + j) * n + k; };
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const int row = id(i, j, k);
        entries.emplace_back(row, row, 6.0 * scale + shift);
        if (i + 1 < n) entries.emplace_back(id(i + 1, j, k), row, -scale);
        if (j + 1 < n) entries.emplace_back(id(i, j + 1, k), row, -scale);
        if (k + 1 < n) entries.emplace_back(id(i, j, k + 1), row, -scale);
      }
  Eigen::SparseMatrix<double> lower(size, size);
  lower.setFromTriplets(entries.begin(), entries.end());
  lower.makeCompressed();
  return lower;
}

Eigen::VectorXd random_vector(Eigen::Index size, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::VectorXd v(size);
  for (Eigen::Index i = 0; i < size; ++i) v[i] = uniform(rng);
  return v;
}

double relative_residual(const Eigen::SparseMatrix<double>& lower, const Eigen::VectorXd& x,
                         const Eigen::VectorXd& b) {
  const Eigen::VectorXd ax = lower.selfadjointView<Eigen::Lower>() * x;
  return (ax - b).norm() / b.norm();
}

class SparseCholeskyOrdering : public ::testing::TestWithParam<SparseCholesky::Ordering> {};

TEST_P(SparseCholeskyOrdering, SolvesAGridSystem) {
  SparseCholesky cholesky(GetParam());
  const auto lower = grid_system(12, 1.0, 1e-3);
  const Eigen::VectorXd b = random_vector(lower.rows(), 1);
  ASSERT_TRUE(cholesky.factorize(lower));
  EXPECT_LT(relative_residual(lower, cholesky.solve(b), b), 1e-10);
}

TEST_P(SparseCholeskyOrdering, ReusesTheAnalysisWhileThePatternHolds) {
  SparseCholesky cholesky(GetParam());
  const Eigen::VectorXd b = random_vector(8 * 8 * 8, 2);
  for (int iteration = 0; iteration < 4; ++iteration) {
    const auto lower = grid_system(8, 1.0 + iteration, 0.5 * iteration + 0.1);
    ASSERT_TRUE(cholesky.factorize(lower));
    EXPECT_LT(relative_residual(lower, cholesky.solve(b), b), 1e-10);
  }
  EXPECT_EQ(cholesky.analyses(), 1);

  // A new pattern (a coupling entry added, as a new contact does) is analysed once more.
  auto coupled = grid_system(8, 1.0, 0.1);
  coupled.coeffRef(200, 3) = -0.01;
  coupled.makeCompressed();
  ASSERT_TRUE(cholesky.factorize(coupled));
  EXPECT_LT(relative_residual(coupled, cholesky.solve(b), b), 1e-10);
  EXPECT_EQ(cholesky.analyses(), 2);
}

TEST_P(SparseCholeskyOrdering, ReportsAnIndefiniteMatrix) {
  SparseCholesky cholesky(GetParam());
  auto lower = grid_system(6, 1.0, 1e-3);
  lower.coeffRef(17, 17) = -5.0;
  EXPECT_FALSE(cholesky.factorize(lower));
}

INSTANTIATE_TEST_SUITE_P(Orderings, SparseCholeskyOrdering,
                         ::testing::Values(SparseCholesky::Ordering::kMetis,
                                           SparseCholesky::Ordering::kAmd));

TEST(SparseCholesky, OrderingsAgree) {
  const auto lower = grid_system(10, 2.0, 0.01);
  const Eigen::VectorXd b = random_vector(lower.rows(), 3);
  SparseCholesky metis(SparseCholesky::Ordering::kMetis);
  SparseCholesky amd(SparseCholesky::Ordering::kAmd);
  ASSERT_TRUE(metis.factorize(lower));
  ASSERT_TRUE(amd.factorize(lower));
  EXPECT_LT((metis.solve(b) - amd.solve(b)).norm() / amd.solve(b).norm(), 1e-10);
}

}  // namespace
}  // namespace grip::solver
