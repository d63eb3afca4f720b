// The device-callable PSD projection (jacobi_psd_projection.hpp) against the host's
// (psd_projection.hpp, Eigen's SelfAdjointEigenSolver) on the matrices projected Newton meets:
// random indefinite ones, PSD ones (returned bit for bit), repeated and clustered eigenvalues,
// rank-deficient ones, and scales from 1e-8 to 1e8; the 3x3, 9x9 (elasticity) and 12x12
// (contacts) sizes.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "solver/kernels/jacobi_psd_projection.hpp"
#include "solver/kernels/psd_projection.hpp"

namespace {

namespace k = grip::solver::kernels;

template <int N>
using Matrix = Eigen::Matrix<double, N, N>;

template <int N>
Matrix<N> random_orthogonal(std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  Matrix<N> a;
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) a(i, j) = normal(rng);
  return Eigen::HouseholderQR<Matrix<N>>(a).householderQ();
}

// Q diag(values) Q^T for a random rotation Q.
template <int N>
Matrix<N> with_eigenvalues(const Eigen::Matrix<double, N, 1>& values, std::mt19937_64& rng) {
  const Matrix<N> q = random_orthogonal<N>(rng);
  const Matrix<N> m = q * values.asDiagonal() * q.transpose();
  return 0.5 * (m + m.transpose());
}

// The kinds of spectra, for case c: random, clustered (pairs within 1e-9), repeated with a
// negative block, rank-deficient with one negative eigenvalue, and tiny negative ones.
template <int N>
Eigen::Matrix<double, N, 1> spectrum(int c, std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  Eigen::Matrix<double, N, 1> values;
  for (int i = 0; i < N; ++i) values[i] = normal(rng);
  switch (c % 5) {
    case 1:
      for (int i = 1; i < N; i += 2) values[i] = values[i - 1] * (1.0 + 1e-9);
      break;
    case 2:
      for (int i = 0; i < N; ++i) values[i] = i < N / 2 ? 2.0 : -1.0;
      break;
    case 3:
      for (int i = 0; i < N; ++i) values[i] = i == 0 ? -1.0 : (i < N / 2 ? 0.0 : 3.0);
      break;
    case 4:
      for (int i = 0; i < N; ++i) values[i] = std::abs(values[i]) + (i == 0 ? -1e-6 : 0.0);
      break;
    default:
      break;
  }
  return values;
}

template <int N>
void compare_with_eigen(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  double worst = 0.0;
  for (int i = 0; i < 500; ++i) {
    const double scale = std::pow(10.0, (i % 17) - 8);  // 1e-8 ... 1e8
    const Matrix<N> h = scale * with_eigenvalues<N>(spectrum<N>(i, rng), rng);
    const Matrix<N> host = k::project_to_psd<N>(h);
    const Matrix<N> device = k::project_to_psd_jacobi<N>(h);
    worst = std::max(worst, (device - host).norm() / h.norm());
    const double smallest =
        Eigen::SelfAdjointEigenSolver<Matrix<N>>(device, Eigen::EigenvaluesOnly).eigenvalues()[0];
    ASSERT_GE(smallest, -1e-13 * h.norm()) << "case " << i;
  }
  EXPECT_LE(worst, 1e-12);
  std::cout << "N = " << N << ": largest relative difference to Eigen's projection " << worst
            << " over 500 matrices\n";
}

TEST(JacobiPsdProjection, AgreesWithEigensProjection3) { compare_with_eigen<3>(1); }
TEST(JacobiPsdProjection, AgreesWithEigensProjection9) { compare_with_eigen<9>(2); }
TEST(JacobiPsdProjection, AgreesWithEigensProjection12) { compare_with_eigen<12>(3); }

TEST(JacobiPsdProjection, ReturnsAPositiveDefiniteMatrixBitForBit) {
  std::mt19937_64 rng(4);
  for (int i = 0; i < 100; ++i) {
    Eigen::Matrix<double, 12, 1> values = spectrum<12>(0, rng).cwiseAbs();
    values.array() += 1e-3;
    const Matrix<12> h = with_eigenvalues<12>(values, rng);
    const Matrix<12> p = k::project_to_psd_jacobi<12>(h);
    EXPECT_TRUE((p.array() == h.array()).all());
  }
}

TEST(JacobiPsdProjection, DiagonalizesToTheEigenvalues) {
  std::mt19937_64 rng(5);
  const Eigen::Matrix<double, 9, 1> values = spectrum<9>(0, rng);
  Matrix<9> a = with_eigenvalues<9>(values, rng), v;
  const Matrix<9> h = a;
  k::jacobi_eigen_decomposition<9>(a, v);
  EXPECT_LE((v * a.diagonal().asDiagonal() * v.transpose() - h).norm(), 1e-13 * h.norm());
  EXPECT_LE((v.transpose() * v - Matrix<9>::Identity()).norm(), 1e-13);
  Eigen::Matrix<double, 9, 1> found = a.diagonal(), expected = values;
  std::sort(found.data(), found.data() + 9);
  std::sort(expected.data(), expected.data() + 9);
  EXPECT_LE((found - expected).norm(), 1e-13 * values.norm());
}

}  // namespace
