#pragma once
// IPC's mollifier for nearly parallel edge-edge contacts: the barrier of an edge pair is scaled
// by m(x), x = ||(ea1 - ea0) x (eb1 - eb0)||^2, so the energy stays smooth as the edges turn
// parallel (where the distance type switches). Value, gradient and Hessian in (ea0, ea1, eb0, eb1).

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "solver/kernels/derivative_maps.hpp"
#include "solver/kernels/hd.hpp"

namespace grip::solver::kernels {

// eps_x = 1e-3 ||ea0 - ea1||^2 ||eb0 - eb1||^2, evaluated at the rest positions.
GRIP_HD inline double edge_edge_mollifier_threshold(const Eigen::Vector3d& ea0_rest,
                                                    const Eigen::Vector3d& ea1_rest,
                                                    const Eigen::Vector3d& eb0_rest,
                                                    const Eigen::Vector3d& eb1_rest) {
  return 1e-3 * (ea0_rest - ea1_rest).squaredNorm() * (eb0_rest - eb1_rest).squaredNorm();
}

// x = ||a x b||^2 = |a|^2 |b|^2 - (a.b)^2 with a = ea1 - ea0, b = eb1 - eb0.
GRIP_HD inline double edge_edge_cross_norm_sq(const Eigen::Vector3d& ea0,
                                              const Eigen::Vector3d& ea1,
                                              const Eigen::Vector3d& eb0,
                                              const Eigen::Vector3d& eb1) {
  return (ea1 - ea0).cross(eb1 - eb0).squaredNorm();
}

namespace detail {
// a = ea1 - ea0, b = eb1 - eb0 as rows over (ea0, ea1, eb0, eb1).
GRIP_HD inline Eigen::Matrix<double, 2, 4> edge_pair_map() {
  Eigen::Matrix<double, 2, 4> S;
  S << -1, 1, 0, 0, 0, 0, -1, 1;
  return S;
}
}  // namespace detail

// dx/da = 2 (|b|^2 a - (a.b) b), dx/db = 2 (|a|^2 b - (a.b) a).
GRIP_HD inline Eigen::Matrix<double, 12, 1> edge_edge_cross_norm_sq_gradient(
    const Eigen::Vector3d& ea0, const Eigen::Vector3d& ea1, const Eigen::Vector3d& eb0,
    const Eigen::Vector3d& eb1) {
  const Eigen::Vector3d a = ea1 - ea0, b = eb1 - eb0;
  const double ab = a.dot(b);
  Eigen::Matrix<double, 6, 1> g;
  g << 2.0 * (b.squaredNorm() * a - ab * b), 2.0 * (a.squaredNorm() * b - ab * a);
  return pull_back_gradient<2, 4>(detail::edge_pair_map(), g);
}

// d2x/da2 = 2 (|b|^2 I - b b^T), d2x/db2 = 2 (|a|^2 I - a a^T),
// d2x/da db = 4 a b^T - 2 b a^T - 2 (a.b) I.
GRIP_HD inline Eigen::Matrix<double, 12, 12> edge_edge_cross_norm_sq_hessian(
    const Eigen::Vector3d& ea0, const Eigen::Vector3d& ea1, const Eigen::Vector3d& eb0,
    const Eigen::Vector3d& eb1) {
  const Eigen::Vector3d a = ea1 - ea0, b = eb1 - eb0;
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  Eigen::Matrix<double, 6, 6> h;
  h.block<3, 3>(0, 0) = 2.0 * (b.squaredNorm() * I - b * b.transpose());
  h.block<3, 3>(3, 3) = 2.0 * (a.squaredNorm() * I - a * a.transpose());
  h.block<3, 3>(0, 3) = 4.0 * a * b.transpose() - 2.0 * b * a.transpose() - 2.0 * a.dot(b) * I;
  h.block<3, 3>(3, 0) = h.block<3, 3>(0, 3).transpose();
  return pull_back_hessian<2, 4>(detail::edge_pair_map(), h);
}

// m(x) = (2 - x / eps_x) x / eps_x for x < eps_x, else 1 (C1 at eps_x, m(0) = 0).
GRIP_HD inline double edge_edge_mollifier(double x, double eps_x) {
  if (x >= eps_x) return 1.0;
  const double r = x / eps_x;
  return (2.0 - r) * r;
}

// m'(x) = 2 (1 - x / eps_x) / eps_x for x < eps_x, else 0.
GRIP_HD inline double edge_edge_mollifier_derivative(double x, double eps_x) {
  if (x >= eps_x) return 0.0;
  return 2.0 * (1.0 - x / eps_x) / eps_x;
}

// m''(x) = -2 / eps_x^2 for x < eps_x, else 0.
GRIP_HD inline double edge_edge_mollifier_second_derivative(double x, double eps_x) {
  if (x >= eps_x) return 0.0;
  return -2.0 / (eps_x * eps_x);
}

GRIP_HD inline double edge_edge_mollifier(const Eigen::Vector3d& ea0, const Eigen::Vector3d& ea1,
                                          const Eigen::Vector3d& eb0, const Eigen::Vector3d& eb1,
                                          double eps_x) {
  return edge_edge_mollifier(edge_edge_cross_norm_sq(ea0, ea1, eb0, eb1), eps_x);
}

// grad m = m'(x) grad x
GRIP_HD inline Eigen::Matrix<double, 12, 1> edge_edge_mollifier_gradient(const Eigen::Vector3d& ea0,
                                                                         const Eigen::Vector3d& ea1,
                                                                         const Eigen::Vector3d& eb0,
                                                                         const Eigen::Vector3d& eb1,
                                                                         double eps_x) {
  const double x = edge_edge_cross_norm_sq(ea0, ea1, eb0, eb1);
  if (x >= eps_x) return Eigen::Matrix<double, 12, 1>::Zero();
  return edge_edge_mollifier_derivative(x, eps_x) *
         edge_edge_cross_norm_sq_gradient(ea0, ea1, eb0, eb1);
}

// hess m = m''(x) grad x grad x^T + m'(x) hess x
GRIP_HD inline Eigen::Matrix<double, 12, 12> edge_edge_mollifier_hessian(const Eigen::Vector3d& ea0,
                                                                         const Eigen::Vector3d& ea1,
                                                                         const Eigen::Vector3d& eb0,
                                                                         const Eigen::Vector3d& eb1,
                                                                         double eps_x) {
  const double x = edge_edge_cross_norm_sq(ea0, ea1, eb0, eb1);
  if (x >= eps_x) return Eigen::Matrix<double, 12, 12>::Zero();
  const Eigen::Matrix<double, 12, 1> g = edge_edge_cross_norm_sq_gradient(ea0, ea1, eb0, eb1);
  return edge_edge_mollifier_second_derivative(x, eps_x) * g * g.transpose() +
         edge_edge_mollifier_derivative(x, eps_x) *
             edge_edge_cross_norm_sq_hessian(ea0, ea1, eb0, eb1);
}

}  // namespace grip::solver::kernels
