// Log barrier on squared distances and the edge-edge mollifier: derivatives against central
// finite differences, the C2 contact at d_hat against the barrier's asymptotic expansion, and the
// mollifier's C1 joint at eps_x.

#include <gtest/gtest.h>
#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "solver/kernels/barrier.hpp"
#include "solver/kernels/edge_edge_mollifier.hpp"
#include "tests/kernels/finite_difference.hpp"

namespace {

namespace k = grip::solver::kernels;
using Eigen::Vector3d;
using grip::test::min_fd_gradient_error;
using grip::test::min_fd_jacobian_error;
using Scalar1 = Eigen::Matrix<double, 1, 1>;
using Vec12 = Eigen::Matrix<double, 12, 1>;

constexpr double kDHatSq = 1e-6;  // d_hat = 1e-3 m, the paper's default

Scalar1 scalar(double v) { return Scalar1::Constant(v); }

TEST(Barrier, DerivativesMatchFiniteDifferences) {
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> exponent(-12.0, std::log10(0.999));
  for (int i = 0; i < 2000; ++i) {
    // Squared distances from 1e-12 d_hat^2 (a distance of 1e-9 m) up to just below d_hat^2.
    const double d = kDHatSq * std::pow(10.0, exponent(rng));
    const auto b = [](const Scalar1& s) { return k::barrier(s[0], kDHatSq); };
    const auto db = [](const Scalar1& s) {
      return scalar(k::barrier_first_derivative(s[0], kDHatSq));
    };
    // The ladder's largest step is 0.1 d: the barrier is only defined for d > 0.
    EXPECT_LT(min_fd_gradient_error(scalar(d), b, scalar(k::barrier_first_derivative(d, kDHatSq)),
                                    d, 1e-300),
              1e-7)
        << "d " << d;
    EXPECT_LT(min_fd_jacobian_error<1>(scalar(d), db,
                                       scalar(k::barrier_second_derivative(d, kDHatSq)), d, 1e-300),
              1e-7)
        << "d " << d;
    // Repulsive and convex inside the active range.
    EXPECT_GT(k::barrier(d, kDHatSq), 0.0);
    EXPECT_LT(k::barrier_first_derivative(d, kDHatSq), 0.0);
    EXPECT_GT(k::barrier_second_derivative(d, kDHatSq), 0.0);
  }
}

TEST(Barrier, IsExactlyZeroFromDHatOn) {
  for (const double d : {kDHatSq, 1.5 * kDHatSq, 1.0}) {
    EXPECT_EQ(k::barrier(d, kDHatSq), 0.0);
    EXPECT_EQ(k::barrier_first_derivative(d, kDHatSq), 0.0);
    EXPECT_EQ(k::barrier_second_derivative(d, kDHatSq), 0.0);
  }
}

// At d = d_hat (1 - delta): b = d_hat^2 delta^3 (1 + O(delta)), b' = -3 d_hat delta^2 (1 +
// O(delta)), b'' = 6 delta (1 + O(delta)). All three vanish at delta = 0, so the barrier is C2 at
// d_hat.
TEST(Barrier, IsC2AtDHat) {
  for (const double delta : {1e-3, 1e-4, 1e-5}) {
    const double d = kDHatSq * (1.0 - delta);
    EXPECT_NEAR(k::barrier(d, kDHatSq) / (kDHatSq * kDHatSq * std::pow(delta, 3)), 1.0, 2 * delta);
    EXPECT_NEAR(k::barrier_first_derivative(d, kDHatSq) / (-3.0 * kDHatSq * delta * delta), 1.0,
                2 * delta);
    EXPECT_NEAR(k::barrier_second_derivative(d, kDHatSq) / (6.0 * delta), 1.0, 2 * delta);
  }
}

// The force is -kappa d/ds b(s^2) for the (unsquared) distance s.
TEST(Barrier, ForceMagnitudeIsTheDistanceDerivative) {
  const double kappa = 3e6;
  for (const double s : {1e-9, 1e-7, 1e-5, 5e-4, 9.9e-4}) {
    const auto energy = [&](const Scalar1& x) { return kappa * k::barrier(x[0] * x[0], kDHatSq); };
    const Scalar1 force = scalar(-k::barrier_force_magnitude(s * s, kDHatSq, kappa));
    EXPECT_LT(min_fd_gradient_error(scalar(s), energy, force, s, 1e-300), 1e-7) << "s " << s;
    EXPECT_LT(force[0], 0.0);
  }
  EXPECT_EQ(k::barrier_force_magnitude(kDHatSq, kDHatSq, kappa), 0.0);
}

TEST(EdgeEdgeMollifier, ScalarIsC1AtThreshold) {
  const double eps = 2.5e-4;
  EXPECT_EQ(k::edge_edge_mollifier(0.0, eps), 0.0);
  EXPECT_DOUBLE_EQ(k::edge_edge_mollifier(eps * (1 - 1e-12), eps), 1.0);
  EXPECT_EQ(k::edge_edge_mollifier(eps, eps), 1.0);
  EXPECT_NEAR(k::edge_edge_mollifier_derivative(eps * (1 - 1e-9), eps) * eps, 0.0, 1e-8);
  EXPECT_DOUBLE_EQ(k::edge_edge_mollifier_derivative(0.0, eps), 2.0 / eps);
  for (const double x : {0.1 * eps, 0.5 * eps, 0.9 * eps}) {
    const auto m = [&](const Scalar1& s) { return k::edge_edge_mollifier(s[0], eps); };
    const auto dm = [&](const Scalar1& s) {
      return scalar(k::edge_edge_mollifier_derivative(s[0], eps));
    };
    EXPECT_LT(min_fd_gradient_error(scalar(x), m, scalar(k::edge_edge_mollifier_derivative(x, eps)),
                                    x, 1e-300),
              1e-8);
    EXPECT_LT(
        min_fd_jacobian_error<1>(
            scalar(x), dm, scalar(k::edge_edge_mollifier_second_derivative(x, eps)), x, 1e-300),
        1e-8);
  }
}

TEST(EdgeEdgeMollifier, ThresholdFromRestLengths) {
  EXPECT_DOUBLE_EQ(k::edge_edge_mollifier_threshold(Vector3d(0, 0, 0), Vector3d(2, 0, 0),
                                                    Vector3d(0, 1, 0), Vector3d(0, 1, 3)),
                   1e-3 * 4.0 * 9.0);
}

// The cross-norm x = ||a x b||^2 and the mollifier m(x(edges)) in the 12 stacked coordinates,
// on random edge pairs turned from parallel (x << eps_x) to well past the threshold.
TEST(EdgeEdgeMollifier, DerivativesMatchFiniteDifferences) {
  std::mt19937_64 rng(22);
  std::uniform_real_distribution<double> u(-1.0, 1.0), angle_exponent(-8.0, 0.0);
  int below = 0, above = 0;
  for (int i = 0; i < 1000; ++i) {
    const Vector3d ea0(u(rng), u(rng), u(rng));
    const Vector3d a =
        Vector3d(u(rng), u(rng), u(rng)).normalized() * (0.5 + 0.5 * std::abs(u(rng)));
    Vector3d axis = a.cross(Vector3d(u(rng), u(rng), u(rng))).normalized();
    const double angle = std::pow(10.0, angle_exponent(rng));
    const Vector3d b =
        (std::cos(angle) * a + std::sin(angle) * axis.cross(a)) * (1.0 + u(rng) * 0.5);
    const Vector3d eb0 = ea0 + Vector3d(u(rng), u(rng), u(rng)) * 0.1;
    Vec12 x;
    x << ea0, ea0 + a, eb0, eb0 + b;
    const double eps_x = k::edge_edge_mollifier_threshold(x.segment<3>(0), x.segment<3>(3),
                                                          x.segment<3>(6), x.segment<3>(9));
    const auto at = [](const Vec12& y, int j) -> Vector3d { return y.segment<3>(3 * j); };
    const auto cross_sq = [&](const Vec12& y) {
      return k::edge_edge_cross_norm_sq(at(y, 0), at(y, 1), at(y, 2), at(y, 3));
    };
    const auto cross_sq_grad = [&](const Vec12& y) {
      return k::edge_edge_cross_norm_sq_gradient(at(y, 0), at(y, 1), at(y, 2), at(y, 3));
    };
    EXPECT_LT(min_fd_gradient_error(x, cross_sq, cross_sq_grad(x), 1.0, 1e-300), 1e-7);
    EXPECT_LT(min_fd_jacobian_error<12>(
                  x, cross_sq_grad,
                  k::edge_edge_cross_norm_sq_hessian(at(x, 0), at(x, 1), at(x, 2), at(x, 3)), 1.0,
                  1e-300),
              1e-7);

    const auto m = [&](const Vec12& y) {
      return k::edge_edge_mollifier(at(y, 0), at(y, 1), at(y, 2), at(y, 3), eps_x);
    };
    const auto m_grad = [&](const Vec12& y) {
      return k::edge_edge_mollifier_gradient(at(y, 0), at(y, 1), at(y, 2), at(y, 3), eps_x);
    };
    const Vec12 g = m_grad(x);
    const Eigen::Matrix<double, 12, 12> h =
        k::edge_edge_mollifier_hessian(at(x, 0), at(x, 1), at(x, 2), at(x, 3), eps_x);
    if (cross_sq(x) >= eps_x) {
      ++above;
      EXPECT_EQ(m(x), 1.0);
      EXPECT_TRUE(g.isZero(0.0));
      EXPECT_TRUE(h.isZero(0.0));
      continue;
    }
    // Away from the joint at eps_x, where the mollifier is only C1.
    if (cross_sq(x) > 0.99 * eps_x) continue;
    ++below;
    EXPECT_LT(min_fd_gradient_error(x, m, g, 1.0, 1e-300), 1e-6);
    EXPECT_LT(min_fd_jacobian_error<12>(x, m_grad, h, 1.0, 1e-300), 1e-6);
  }
  EXPECT_GT(below, 300);
  EXPECT_GT(above, 100);
}

}  // namespace
