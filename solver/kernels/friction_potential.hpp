#pragma once
// IPC's lagged dissipative friction potential of one contact with N vertices:
// D(x) = mu lambda f0(||u||), u = T_k^T (x - x_prev), with the tangential operator T_k
// (3N x 2, relative_velocity.hpp) and the normal force lambda frozen at the lagged state.
// The argument dx is x - x_prev and eps is the displacement threshold eps_v * dt.

#include <Eigen/Core>
#include <cmath>

#include "solver/kernels/friction_mollifier.hpp"
#include "solver/kernels/hd.hpp"

namespace grip::solver::kernels {

template <int N>
GRIP_HD inline double friction_potential(const Eigen::Matrix<double, 3 * N, 1>& dx,
                                         const Eigen::Matrix<double, 3 * N, 2>& tangent_op,
                                         double mu_lambda, double eps) {
  const Eigen::Vector2d u = tangent_op.transpose() * dx;
  return mu_lambda * friction_f0(u.norm(), eps);
}

// grad D = mu lambda (f1(y) / y) T_k u, y = ||u||.
template <int N>
GRIP_HD inline Eigen::Matrix<double, 3 * N, 1> friction_potential_gradient(
    const Eigen::Matrix<double, 3 * N, 1>& dx, const Eigen::Matrix<double, 3 * N, 2>& tangent_op,
    double mu_lambda, double eps) {
  const Eigen::Vector2d u = tangent_op.transpose() * dx;
  return (mu_lambda * friction_f1_over_y(u.norm(), eps)) * (tangent_op * u);
}

// hess D = mu lambda T_k [ (f1/y) I + ((f1/y)' / y) u u^T ] T_k^T. The 2x2 middle matrix has
// eigenvalue f1/y > 0 across u and f1'(y) >= 0 along u, so the Hessian is positive
// semi-definite as it stands: the exact Hessian is also the PSD-projected one of IPC.
template <int N>
GRIP_HD inline Eigen::Matrix<double, 3 * N, 3 * N> friction_potential_hessian(
    const Eigen::Matrix<double, 3 * N, 1>& dx, const Eigen::Matrix<double, 3 * N, 2>& tangent_op,
    double mu_lambda, double eps) {
  const Eigen::Vector2d u = tangent_op.transpose() * dx;
  const double y = u.norm();
  Eigen::Matrix2d inner = friction_f1_over_y(y, eps) * Eigen::Matrix2d::Identity();
  if (y > 0.0) inner += (friction_f1_over_y_derivative(y, eps) / y) * u * u.transpose();
  return mu_lambda * tangent_op * inner * tangent_op.transpose();
}

}  // namespace grip::solver::kernels
