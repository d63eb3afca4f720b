// Lagged friction kernels: the smoothed mollifier f0 / f1, tangent bases, closest-point
// coordinates, the relative-velocity operator and the dissipative potential with its gradient and
// (positive semi-definite) Hessian, checked against their defining properties and finite
// differences.

#include <gtest/gtest.h>
#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "solver/kernels/closest_point.hpp"
#include "solver/kernels/friction_mollifier.hpp"
#include "solver/kernels/friction_potential.hpp"
#include "solver/kernels/relative_velocity.hpp"
#include "solver/kernels/tangent_basis.hpp"
#include "tests/kernels/finite_difference.hpp"

namespace {

namespace k = grip::solver::kernels;
using Eigen::Vector3d;
using grip::test::min_fd_gradient_error;
using grip::test::min_fd_jacobian_error;
using Scalar1 = Eigen::Matrix<double, 1, 1>;
using Basis = Eigen::Matrix<double, 3, 2>;

constexpr double kEps = 1e-5;  // eps_v dt = 1e-3 m/s * 0.01 s, the paper's defaults

class Random {
 public:
  explicit Random(std::uint64_t seed) : rng_(seed) {}
  double uniform(double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng_);
  }
  Vector3d point() { return Vector3d(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)); }

 private:
  std::mt19937_64 rng_;
};

TEST(FrictionMollifier, F1IsTheDerivativeOfF0AndJoinsC1) {
  EXPECT_DOUBLE_EQ(k::friction_f0(kEps, kEps), kEps);
  EXPECT_NEAR(k::friction_f0(kEps * (1 - 1e-12), kEps), kEps, 2e-12 * kEps);
  EXPECT_DOUBLE_EQ(k::friction_f0(0.0, kEps), kEps / 3.0);
  EXPECT_EQ(k::friction_f1(0.0, kEps), 0.0);
  EXPECT_DOUBLE_EQ(k::friction_f1(kEps * (1 - 1e-12), kEps), 1.0);
  EXPECT_EQ(k::friction_f1(2 * kEps, kEps), 1.0);
  EXPECT_DOUBLE_EQ(k::friction_f1_over_y(0.0, kEps), 2.0 / kEps);
  // (f1 / y)' is continuous at eps: -1 / eps^2 from both sides.
  EXPECT_DOUBLE_EQ(k::friction_f1_over_y_derivative(kEps * (1 - 1e-12), kEps),
                   k::friction_f1_over_y_derivative(kEps, kEps));
  for (const double y :
       {1e-3 * kEps, 0.3 * kEps, 0.7 * kEps, 0.999 * kEps, 1.5 * kEps, 10 * kEps}) {
    const auto f0 = [](const Scalar1& s) { return k::friction_f0(s[0], kEps); };
    const auto f1_over_y = [](const Scalar1& s) { return k::friction_f1_over_y(s[0], kEps); };
    const Scalar1 at = Scalar1::Constant(y);
    EXPECT_LT(min_fd_gradient_error(at, f0, Scalar1::Constant(k::friction_f1(y, kEps)),
                                    std::min(y, 1e-3 * kEps), 1e-300),
              1e-8)
        << "y " << y;
    EXPECT_LT(min_fd_gradient_error(at, f1_over_y,
                                    Scalar1::Constant(k::friction_f1_over_y_derivative(y, kEps)),
                                    std::min(y, 1e-3 * kEps), 1e-300),
              1e-8)
        << "y " << y;
    EXPECT_DOUBLE_EQ(k::friction_f1_over_y(y, kEps) * y, k::friction_f1(y, kEps));
    // f1 rises monotonically from 0 to 1.
    EXPECT_GE(k::friction_f1(y, kEps), 0.0);
    EXPECT_LE(k::friction_f1(y, kEps), 1.0);
  }
}

// Columns orthonormal and perpendicular to the contact normal.
void expect_tangent_basis(const Basis& basis, const Vector3d& normal) {
  EXPECT_LT((basis.transpose() * basis - Eigen::Matrix2d::Identity()).norm(), 1e-14);
  EXPECT_LT((basis.transpose() * normal.normalized()).norm(), 1e-12);
}

TEST(TangentBasis, IsOrthonormalAndTangentForEveryContactType) {
  Random r(41);
  for (int i = 0; i < 500; ++i) {
    const Vector3d p = r.point(), v0 = r.point(), v1 = r.point(), v2 = r.point(), v3 = r.point();
    expect_tangent_basis(k::point_point_tangent_basis(p, v0), p - v0);
    const double alpha = k::point_edge_closest_point(p, v0, v1);
    expect_tangent_basis(k::point_edge_tangent_basis(p, v0, v1), p - (v0 + alpha * (v1 - v0)));
    expect_tangent_basis(k::point_triangle_tangent_basis(p, v0, v1, v2), (v1 - v0).cross(v2 - v0));
    expect_tangent_basis(k::edge_edge_tangent_basis(v0, v1, v2, v3), (v1 - v0).cross(v3 - v2));
  }
  // A point on the edge's line, and parallel edges: no normal from the cross product, still a
  // valid basis containing the edge direction.
  const Vector3d e0(0, 0, 0), e1(1, 1, 0);
  const Basis on_line = k::point_edge_tangent_basis(Vector3d(2, 2, 0), e0, e1);
  EXPECT_TRUE(on_line.allFinite());
  EXPECT_LT((on_line.transpose() * on_line - Eigen::Matrix2d::Identity()).norm(), 1e-14);
  EXPECT_LT(on_line.col(0).cross(e1.normalized()).norm(), 1e-15);
  const Basis parallel = k::edge_edge_tangent_basis(e0, e1, Vector3d(0, 0, 1), Vector3d(2, 2, 1));
  EXPECT_TRUE(parallel.allFinite());
  EXPECT_LT((parallel.transpose() * parallel - Eigen::Matrix2d::Identity()).norm(), 1e-14);
}

// Closest points are defined by the residual being orthogonal to the primitives' directions; the
// relative-velocity operator applied to the positions reproduces that residual, gives zero for a
// common translation, and its tangential part vanishes at the lagged configuration.
TEST(RelativeVelocity, ClosestPointsAndOperatorsAreConsistent) {
  Random r(42);
  for (int i = 0; i < 500; ++i) {
    const Vector3d p = r.point(), v0 = r.point(), v1 = r.point(), v2 = r.point(), v3 = r.point();
    const Vector3d shift = r.point();

    const double alpha = k::point_edge_closest_point(p, v0, v1);
    const Vector3d pe_residual = p - (v0 + alpha * (v1 - v0));
    EXPECT_NEAR(pe_residual.dot(v1 - v0), 0.0, 1e-13);
    Eigen::Matrix<double, 9, 1> x9, t9;
    x9 << p, v0, v1;
    t9 << shift, shift, shift;
    const Eigen::Matrix<double, 3, 9> g_pe = k::point_edge_relative_velocity_jacobian(alpha);
    EXPECT_LT((g_pe * x9 - pe_residual).norm(), 1e-14);
    EXPECT_LT((g_pe * t9).norm(), 1e-14);
    EXPECT_LT(
        (k::tangent_operator<3>(g_pe, k::point_edge_tangent_basis(p, v0, v1)).transpose() * x9)
            .norm(),
        1e-12);

    const Eigen::Vector2d beta = k::point_triangle_closest_point(p, v0, v1, v2);
    const Vector3d pt_residual = p - (v0 + beta[0] * (v1 - v0) + beta[1] * (v2 - v0));
    EXPECT_NEAR(pt_residual.dot(v1 - v0), 0.0, 1e-12);
    EXPECT_NEAR(pt_residual.dot(v2 - v0), 0.0, 1e-12);
    Eigen::Matrix<double, 12, 1> x12, t12;
    x12 << p, v0, v1, v2;
    t12 << shift, shift, shift, shift;
    const Eigen::Matrix<double, 3, 12> g_pt = k::point_triangle_relative_velocity_jacobian(beta);
    EXPECT_LT((g_pt * x12 - pt_residual).norm(), 1e-13);
    EXPECT_LT((g_pt * t12).norm(), 1e-13);
    EXPECT_LT(
        (k::tangent_operator<4>(g_pt, k::point_triangle_tangent_basis(p, v0, v1, v2)).transpose() *
         x12)
            .norm(),
        1e-11);

    const Eigen::Vector2d ab = k::edge_edge_closest_point(v0, v1, v2, v3);
    const Vector3d ee_residual = (v0 + ab[0] * (v1 - v0)) - (v2 + ab[1] * (v3 - v2));
    EXPECT_NEAR(ee_residual.dot(v1 - v0), 0.0, 1e-12);
    EXPECT_NEAR(ee_residual.dot(v3 - v2), 0.0, 1e-12);
    x12 << v0, v1, v2, v3;
    const Eigen::Matrix<double, 3, 12> g_ee = k::edge_edge_relative_velocity_jacobian(ab);
    EXPECT_LT((g_ee * x12 - ee_residual).norm(), 1e-13);
    EXPECT_LT((g_ee * t12).norm(), 1e-13);
    EXPECT_LT(
        (k::tangent_operator<4>(g_ee, k::edge_edge_tangent_basis(v0, v1, v2, v3)).transpose() * x12)
            .norm(),
        1e-11);

    Eigen::Matrix<double, 6, 1> x6;
    x6 << p, v0;
    EXPECT_LT((k::point_point_relative_velocity_jacobian() * x6 - (p - v0)).norm(), 0.0 + 1e-15);
  }
}

// D, grad D and hess D for a point-triangle contact at random lagged configurations, with
// tangential displacements from 1e-4 eps (static) through eps to 1e3 eps (sliding).
TEST(FrictionPotential, DerivativesMatchFiniteDifferencesAndHessianIsPsd) {
  Random r(43);
  using Vec12 = Eigen::Matrix<double, 12, 1>;
  const double mu_lambda = 3.5 * 20.0;
  for (int i = 0; i < 1000; ++i) {
    const Vector3d p = r.point(), t0 = r.point(), t1 = r.point(), t2 = r.point();
    const Eigen::Matrix<double, 12, 2> op =
        k::tangent_operator<4>(k::point_triangle_relative_velocity_jacobian(
                                   k::point_triangle_closest_point(p, t0, t1, t2)),
                               k::point_triangle_tangent_basis(p, t0, t1, t2));
    Vec12 dx;
    for (int j = 0; j < 12; ++j) dx[j] = r.uniform(-1, 1);
    const double target = kEps * std::pow(10.0, r.uniform(-4, 3));
    const double y = (op.transpose() * dx).norm();
    if (y == 0.0) continue;
    dx *= target / y;

    const auto energy = [&](const Vec12& z) {
      return k::friction_potential<4>(z, op, mu_lambda, kEps);
    };
    const auto gradient = [&](const Vec12& z) {
      return k::friction_potential_gradient<4>(z, op, mu_lambda, kEps);
    };
    const Eigen::Matrix<double, 12, 12> hess =
        k::friction_potential_hessian<4>(dx, op, mu_lambda, kEps);
    // Steps from 0.1 of the displacement down: the potential's pieces join at |u| = eps.
    EXPECT_LT(min_fd_gradient_error(dx, energy, gradient(dx), target, 1e-300), 1e-6)
        << "|u| / eps " << target / kEps;
    if (std::abs(target - kEps) > 1e-2 * kEps) {
      EXPECT_LT(min_fd_jacobian_error<12>(dx, gradient, hess, target, 1e-300), 1e-6)
          << "|u| / eps " << target / kEps;
    }
    const double min_eig =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 12, 12>>(hess, Eigen::EigenvaluesOnly)
            .eigenvalues()
            .minCoeff();
    EXPECT_GE(min_eig, -1e-12 * hess.norm());
  }
}

// With T_k embedding the tangent plane isometrically, grad D is the friction force in the plane:
// magnitude mu lambda when sliding (Coulomb), less while static, and opposing the motion.
TEST(FrictionPotential, ForceIsCoulombWhenSliding) {
  Eigen::Matrix<double, 6, 2> op = Eigen::Matrix<double, 6, 2>::Zero();
  op(0, 0) = op(1, 1) = 1.0;  // u = (dx_0, dx_1)
  const double mu_lambda = 2.0;
  for (const double y : {0.0, 0.1 * kEps, 0.9 * kEps, kEps, 3 * kEps, 1e3 * kEps}) {
    Eigen::Matrix<double, 6, 1> dx = Eigen::Matrix<double, 6, 1>::Zero();
    dx[0] = 0.6 * y;
    dx[1] = -0.8 * y;
    const Eigen::Matrix<double, 6, 1> g =
        k::friction_potential_gradient<2>(dx, op, mu_lambda, kEps);
    EXPECT_NEAR(g.norm(), mu_lambda * k::friction_f1(y, kEps), 1e-12);
    if (y >= kEps) {
      EXPECT_NEAR(g.norm(), mu_lambda, 1e-12);
    }
    if (y > 0.0) {
      EXPECT_NEAR(g.dot(dx), g.norm() * dx.norm(), 1e-12 * g.norm() * dx.norm());
    }
  }
  // Zero displacement: zero force, Hessian mu lambda (2 / eps) on the tangent plane.
  const Eigen::Matrix<double, 6, 6> h =
      k::friction_potential_hessian<2>(Eigen::Matrix<double, 6, 1>::Zero(), op, mu_lambda, kEps);
  EXPECT_DOUBLE_EQ(h(0, 0), mu_lambda * 2.0 / kEps);
  EXPECT_DOUBLE_EQ(h(1, 1), mu_lambda * 2.0 / kEps);
  EXPECT_EQ(h(0, 1), 0.0);
}

}  // namespace
