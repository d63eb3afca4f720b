#pragma once
// The relative velocity of a contact pair as a linear map Gamma (3 x 3N) of its stacked vertex
// velocities: velocity of the first primitive's closest point minus the second's. With a tangent
// basis T (3x2), T^T Gamma gives the 2D tangential relative velocity of lagged friction.

#include <Eigen/Core>

#include "solver/kernels/hd.hpp"

namespace grip::solver::kernels {

namespace detail {
template <int N>
GRIP_HD inline Eigen::Matrix<double, 3, 3 * N> weighted_identities(const double (&w)[N]) {
  Eigen::Matrix<double, 3, 3 * N> gamma;
  for (int i = 0; i < N; ++i)
    gamma.template block<3, 3>(0, 3 * i) = w[i] * Eigen::Matrix3d::Identity();
  return gamma;
}
}  // namespace detail

// v_p0 - v_p1
GRIP_HD inline Eigen::Matrix<double, 3, 6> point_point_relative_velocity_jacobian() {
  return detail::weighted_identities<2>({1.0, -1.0});
}

// v_p - ((1 - alpha) v_e0 + alpha v_e1), alpha from point_edge_closest_point.
GRIP_HD inline Eigen::Matrix<double, 3, 9> point_edge_relative_velocity_jacobian(double alpha) {
  return detail::weighted_identities<3>({1.0, -(1.0 - alpha), -alpha});
}

// v_p - ((1 - b1 - b2) v_t0 + b1 v_t1 + b2 v_t2), beta from point_triangle_closest_point.
GRIP_HD inline Eigen::Matrix<double, 3, 12> point_triangle_relative_velocity_jacobian(
    const Eigen::Vector2d& beta) {
  return detail::weighted_identities<4>({1.0, -(1.0 - beta[0] - beta[1]), -beta[0], -beta[1]});
}

// ((1 - alpha) v_ea0 + alpha v_ea1) - ((1 - beta) v_eb0 + beta v_eb1), (alpha, beta) from
// edge_edge_closest_point.
GRIP_HD inline Eigen::Matrix<double, 3, 12> edge_edge_relative_velocity_jacobian(
    const Eigen::Vector2d& coords) {
  return detail::weighted_identities<4>(
      {1.0 - coords[0], coords[0], -(1.0 - coords[1]), -coords[1]});
}

// The tangential operator T_k = Gamma^T T (3N x 2): u = T_k^T v is the 2D tangential relative
// velocity (or displacement, for v = x - x_prev).
template <int N>
GRIP_HD inline Eigen::Matrix<double, 3 * N, 2> tangent_operator(
    const Eigen::Matrix<double, 3, 3 * N>& gamma, const Eigen::Matrix<double, 3, 2>& basis) {
  return gamma.transpose() * basis;
}

}  // namespace grip::solver::kernels
