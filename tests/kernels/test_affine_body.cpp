// Affine body kernels: the DOF layout and Jacobian, the orthogonality potential's exact zeros
// and analytic values, its derivatives against central differences, and PSD projection.
#include "solver/kernels/affine_body.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <random>

#include "solver/kernels/psd_projection.hpp"
#include "tests/kernels/finite_difference.hpp"

namespace {

using namespace grip::solver::kernels;
using grip::test::fd_gradient;
using grip::test::fd_jacobian;
using grip::test::relatively_close;

constexpr double kStiffness = 1e8;  // Pa
constexpr double kVolume = 2e-4;    // m^3

// The 12x12 Hessian: the kernel's 9x9 block in the rows of A, PSD-projected if asked.
Matrix12d orthogonality_hessian(const Vector12d& q, bool project) {
  const Eigen::Matrix<double, 9, 9> block = affine_body_orthogonality_block(q, kStiffness, kVolume);
  Matrix12d h = Matrix12d::Zero();
  h.block<9, 9>(3, 3) = project ? project_to_psd<9>(block) : block;
  return h;
}

Eigen::Matrix3d random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
}

TEST(AffineBody, LayoutAndJacobian) {
  for (int trial = 0; trial < 100; ++trial) {
    const Vector12d q = Vector12d::Random();
    const Eigen::Vector3d xbar = Eigen::Vector3d::Random();
    const Eigen::Matrix3d a = affine_body_matrix(q);
    // Rows of A are q[3:6], q[6:9], q[9:12]; p is q[0:3].
    EXPECT_EQ(a(1, 2), q[3 + 3 * 1 + 2]);
    EXPECT_EQ(affine_body_dofs(a, q.head<3>()), q);
    const Eigen::Vector3d x = affine_body_position(q, xbar);
    EXPECT_TRUE(relatively_close(x, a * xbar + q.head<3>(), 1e-15, 1e-15));
    // x is linear in q: J(xbar) q reproduces it and J is its exact derivative.
    const Eigen::Matrix<double, 3, 12> j = affine_body_jacobian(xbar);
    EXPECT_TRUE(relatively_close(j * q, x, 1e-14, 1e-14));
    auto position = [&](const Vector12d& v) { return affine_body_position(v, xbar); };
    EXPECT_TRUE(relatively_close(j, fd_jacobian<3, 12>(q, position, 1e-6), 1e-9, 1e-9));
  }
  // The identity map leaves every point where it is.
  const Vector12d identity = affine_body_dofs(Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
  EXPECT_EQ(affine_body_position(identity, Eigen::Vector3d(1, 2, 3)), Eigen::Vector3d(1, 2, 3));
}

TEST(AffineBody, OrthogonalityPotentialVanishesForEveryRotation) {
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 1000; ++trial) {
    Eigen::Matrix3d r = random_rotation(rng);
    if (trial % 4 == 0) r.row(0) *= -1.0;  // reflections are orthogonal too
    const Vector12d q = affine_body_dofs(r, Eigen::Vector3d::Random());
    const double scale = kStiffness * kVolume;
    EXPECT_LT(affine_body_orthogonality_energy(q, kStiffness, kVolume), 1e-28 * scale);
    EXPECT_LT(affine_body_orthogonality_gradient(q, kStiffness, kVolume).norm(), 1e-13 * scale);
  }
}

TEST(AffineBody, OrthogonalityPotentialAnalyticValues) {
  // A = diag(a, 1, 1): ||A A^T - I||^2 = (a^2 - 1)^2. A = s R: 3 (s^2 - 1)^2.
  std::mt19937_64 rng(9);
  for (double a : {0.0, 0.5, 1.0, 1.5, 3.0}) {
    const Vector12d q =
        affine_body_dofs(Eigen::Vector3d(a, 1, 1).asDiagonal(), Eigen::Vector3d::Zero());
    EXPECT_NEAR(affine_body_orthogonality_energy(q, kStiffness, kVolume),
                kStiffness * kVolume * (a * a - 1) * (a * a - 1), 1e-9 * kStiffness * kVolume);
    const double s = 0.5 + a;
    const Vector12d scaled = affine_body_dofs(s * random_rotation(rng), Eigen::Vector3d::Ones());
    EXPECT_NEAR(affine_body_orthogonality_energy(scaled, kStiffness, kVolume),
                3 * kStiffness * kVolume * (s * s - 1) * (s * s - 1),
                1e-9 * kStiffness * kVolume * (1 + s * s * s * s));
  }
}

TEST(AffineBody, OrthogonalityDerivativesMatchCentralDifferences) {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 3000; ++trial) {
    // Near a rotation, strongly stretched/sheared, and nearly singular A.
    Eigen::Matrix3d a = random_rotation(rng);
    const double spread = trial % 3 == 0 ? 1e-3 : trial % 3 == 1 ? 1.0 : 0.0;
    for (int i = 0; i < 9; ++i) a(i) += spread * u(rng);
    if (trial % 3 == 2) a.col(0) = 1e-4 * a.col(0);
    const Vector12d q = affine_body_dofs(a, Eigen::Vector3d(u(rng), u(rng), u(rng)));
    auto energy = [](const Vector12d& v) {
      return affine_body_orthogonality_energy(v, kStiffness, kVolume);
    };
    auto gradient = [](const Vector12d& v) {
      return affine_body_orthogonality_gradient(v, kStiffness, kVolume);
    };
    const double h = 1e-6;
    const double scale = kStiffness * kVolume;
    ASSERT_TRUE(relatively_close(gradient(q), fd_gradient<12>(q, energy, h), 1e-6, 1e-7 * scale))
        << "trial " << trial;
    ASSERT_TRUE(relatively_close(orthogonality_hessian(q, false),
                                 fd_jacobian<12, 12>(q, gradient, h), 1e-7, 1e-7 * scale))
        << "trial " << trial;
  }
}

TEST(AffineBody, ProjectedHessianIsPsdAndUnchangedWhenAlreadyPsd) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int indefinite = 0;
  for (int trial = 0; trial < 500; ++trial) {
    Eigen::Matrix3d a = random_rotation(rng);
    // Shrunk A (||a_i|| < 1) makes the potential concave in some directions.
    a *= trial % 2 ? 0.3 : 1.0;
    for (int i = 0; i < 9; ++i) a(i) += 0.2 * u(rng);
    const Vector12d q = affine_body_dofs(a, Eigen::Vector3d::Zero());
    const Matrix12d h = orthogonality_hessian(q, false);
    const Matrix12d p = orthogonality_hessian(q, true);
    const Eigen::SelfAdjointEigenSolver<Matrix12d> before(h);
    const Eigen::SelfAdjointEigenSolver<Matrix12d> after(p);
    const double tol = 1e-12 * h.norm();
    EXPECT_GE(after.eigenvalues().minCoeff(), -tol);
    if (before.eigenvalues().minCoeff() < -tol) {
      ++indefinite;
    } else {
      EXPECT_LT((p - h).norm(), 1e-10 * h.norm());
    }
    EXPECT_TRUE(p.topRows<3>().isZero() && p.leftCols<3>().isZero());
  }
  EXPECT_GT(indefinite, 100);
  // At a rotation the potential is at its minimum: the Hessian is PSD and stays unchanged.
  const Vector12d q = affine_body_dofs(random_rotation(rng), Eigen::Vector3d::Zero());
  const Matrix12d h = orthogonality_hessian(q, false);
  EXPECT_LT((orthogonality_hessian(q, true) - h).norm(), 1e-10 * h.norm());
}

}  // namespace
