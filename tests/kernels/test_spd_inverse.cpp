// The device-callable inverse of a small SPD matrix (spd_inverse.hpp) against Eigen's LLT on the
// sizes block-Jacobi meets (3: an FEM vertex, 12: an affine body, and every size between),
// condition numbers up to 1e10; only the lower triangle is read; a matrix that is not positive
// definite is refused.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "solver/kernels/spd_inverse.hpp"

namespace {

namespace k = grip::solver::kernels;

// Q diag(values) Q^T with eigenvalues spread log-uniformly over [1, condition].
Eigen::MatrixXd random_spd(int n, double condition, std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  Eigen::MatrixXd a(n, n);
  for (double& x : a.reshaped()) x = normal(rng);
  const Eigen::MatrixXd q = Eigen::HouseholderQR<Eigen::MatrixXd>(a).householderQ();
  Eigen::VectorXd values(n);
  for (int i = 0; i < n; ++i) values[i] = std::pow(condition, n > 1 ? double(i) / (n - 1) : 0.0);
  const Eigen::MatrixXd m = q * values.asDiagonal() * q.transpose();
  return 0.5 * (m + m.transpose());
}

TEST(SpdInverse, MatchesEigensCholeskyOnEverySizeUpToTwelve) {
  std::mt19937_64 rng(5);
  for (int n = 1; n <= k::kMaxSpdInverseSize; ++n) {
    for (const double condition : {1.0, 1e3, 1e6, 1e10}) {
      SCOPED_TRACE("n = " + std::to_string(n) + ", condition " + std::to_string(condition));
      const Eigen::MatrixXd a = random_spd(n, condition, rng);
      Eigen::MatrixXd inverse(n, n);
      ASSERT_TRUE(k::spd_inverse(a.data(), n, inverse.data()));
      const Eigen::MatrixXd reference = a.llt().solve(Eigen::MatrixXd::Identity(n, n));
      // Both are backward stable: they agree to the condition number times round-off.
      EXPECT_LE((inverse - reference).norm(), 1e-15 * condition * 50 * reference.norm());
      EXPECT_LE((inverse - inverse.transpose()).norm(), 1e-15 * condition * 50 * inverse.norm());
    }
  }
}

TEST(SpdInverse, ReadsOnlyTheLowerTriangle) {
  std::mt19937_64 rng(6);
  Eigen::MatrixXd a = random_spd(12, 100.0, rng);
  Eigen::MatrixXd expected(12, 12), inverse(12, 12);
  ASSERT_TRUE(k::spd_inverse(a.data(), 12, expected.data()));
  a.triangularView<Eigen::StrictlyUpper>().setConstant(1e300);
  ASSERT_TRUE(k::spd_inverse(a.data(), 12, inverse.data()));
  EXPECT_EQ(inverse, expected);
}

TEST(SpdInverse, RefusesAMatrixThatIsNotPositiveDefinite) {
  std::mt19937_64 rng(7);
  for (const int n : {3, 12}) {
    Eigen::MatrixXd a = random_spd(n, 10.0, rng);
    Eigen::MatrixXd inverse(n, n);
    const Eigen::MatrixXd negative = -a;
    EXPECT_FALSE(k::spd_inverse(negative.data(), n, inverse.data()));
    // One eigenvalue pushed below zero: only a late pivot sees it.
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(a);
    const Eigen::VectorXd v = eigen.eigenvectors().col(0);
    a -= (eigen.eigenvalues()[0] + 0.5) * v * v.transpose();
    EXPECT_FALSE(k::spd_inverse(a.data(), n, inverse.data()));
    const Eigen::MatrixXd zero = Eigen::MatrixXd::Zero(n, n);
    EXPECT_FALSE(k::spd_inverse(zero.data(), n, inverse.data()));
  }
}

}  // namespace
