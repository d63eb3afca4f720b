// Per-element PSD projection: the result has no negative eigenvalue, PSD input comes back
// unchanged, and the projection satisfies the optimality conditions of the nearest PSD matrix.

#include <gtest/gtest.h>
#include <Eigen/Dense>
#include <random>

#include "solver/kernels/psd_projection.hpp"

namespace {

namespace k = grip::solver::kernels;

template <int N>
Eigen::Matrix<double, N, N> random_symmetric(std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  Eigen::Matrix<double, N, N> a;
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) a(i, j) = normal(rng);
  return 0.5 * (a + a.transpose());
}

template <int N>
double min_eigenvalue(const Eigen::Matrix<double, N, N>& m) {
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>>(m, Eigen::EigenvaluesOnly)
      .eigenvalues()
      .minCoeff();
}

// P = proj(H) is the nearest PSD matrix iff P is PSD, H - P is negative semi-definite and
// P (H - P) = 0 (complementarity in the PSD cone).
template <int N>
void check_projection(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Matrix<double, N, N> h = random_symmetric<N>(rng);
    const Eigen::Matrix<double, N, N> p = k::project_to_psd<N>(h);
    const double scale = h.norm();
    EXPECT_TRUE(p.isApprox(p.transpose(), 1e-14));
    EXPECT_GE(min_eigenvalue<N>(p), -1e-13 * scale);
    EXPECT_LE(-min_eigenvalue<N>(Eigen::Matrix<double, N, N>(p - h)), 1e-13 * scale);
    EXPECT_LT((p * (h - p)).norm(), 1e-13 * scale * scale);
    // Idempotent up to round-off.
    EXPECT_LT((k::project_to_psd<N>(p) - p).norm(), 1e-13 * scale);
  }
}

TEST(PsdProjection, IsTheNearestPsdMatrix) {
  check_projection<3>(31);
  check_projection<6>(32);
  check_projection<9>(33);
  check_projection<12>(34);
}

TEST(PsdProjection, LeavesPsdMatricesUnchanged) {
  std::mt19937_64 rng(35);
  for (int i = 0; i < 100; ++i) {
    const Eigen::Matrix<double, 12, 12> a = random_symmetric<12>(rng);
    // A^T A + I is positive definite.
    const Eigen::Matrix<double, 12, 12> pd =
        a.transpose() * a + Eigen::Matrix<double, 12, 12>::Identity();
    EXPECT_EQ(k::project_to_psd<12>(pd), pd);
  }
  const Eigen::Matrix<double, 12, 12> zero = Eigen::Matrix<double, 12, 12>::Zero();
  EXPECT_EQ(k::project_to_psd<12>(zero), zero);
}

TEST(PsdProjection, ClampsKnownSpectrum) {
  // diag(2, -1, 0) in a rotated frame projects to diag(2, 0, 0) in that frame.
  const Eigen::Matrix3d q = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
  const Eigen::Matrix3d h = q * Eigen::Vector3d(2, -1, 0).asDiagonal() * q.transpose();
  const Eigen::Matrix3d expected = q * Eigen::Vector3d(2, 0, 0).asDiagonal() * q.transpose();
  EXPECT_LT((k::project_to_psd<3>(h) - expected).norm(), 1e-14);
  // Negative definite goes to zero.
  EXPECT_LT(k::project_to_psd<3>(Eigen::Matrix3d(-h * h - Eigen::Matrix3d::Identity())).norm(),
            1e-14);
}

}  // namespace
