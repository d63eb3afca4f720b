#pragma once
// IPC's barrier of one contact (a point and a triangle, or two edges) in its four vertices'
// positions: kappa m b(d) with d the unsquared distance, b the log barrier (barrier.hpp) and m
// the mollifier of nearly parallel edges (1 for a point and a triangle), with its 12-vector
// gradient and, on request, its 12x12 Hessian (not projected), or its value alone; and its
// normal force. The CPU engine's BarrierTerm and the data-parallel engine's stages both
// evaluate them.
#include <Eigen/Core>
#include <cmath>

#include "solver/kernels/barrier.hpp"
#include "solver/kernels/distance.hpp"
#include "solver/kernels/edge_edge_mollifier.hpp"
#include "solver/kernels/hd.hpp"

namespace grip::solver::kernels {

struct ContactBarrier {
  double value = 0.0;
  Eigen::Matrix<double, 12, 1> gradient = Eigen::Matrix<double, 12, 1>::Zero();
  Eigen::Matrix<double, 12, 12> hessian = Eigen::Matrix<double, 12, 12>::Zero();
};

GRIP_HD inline double contact_squared_distance(bool edge_edge, const Eigen::Vector3d x[4]) {
  return edge_edge ? edge_edge_distance_sq(x[0], x[1], x[2], x[3])
                   : point_triangle_distance_sq(x[0], x[1], x[2], x[3]);
}

namespace contact_barrier_detail {

using Vector12 = Eigen::Matrix<double, 12, 1>;
using Matrix12 = Eigen::Matrix<double, 12, 12>;

// The squared distance's gradient and (optionally) Hessian in the four vertices' positions.
GRIP_HD inline void squared_distance_derivatives(bool edge_edge, const Eigen::Vector3d x[4],
                                                 bool with_hessian, Vector12& grad_s,
                                                 Matrix12& hess_s) {
  if (edge_edge) {
    grad_s = edge_edge_distance_sq_gradient(x[0], x[1], x[2], x[3]);
    if (with_hessian) hess_s = edge_edge_distance_sq_hessian(x[0], x[1], x[2], x[3]);
  } else {
    grad_s = point_triangle_distance_sq_gradient(x[0], x[1], x[2], x[3]);
    if (with_hessian) hess_s = point_triangle_distance_sq_hessian(x[0], x[1], x[2], x[3]);
  }
}

// kappa m b from kappa b's derivatives (grad_b, hess_b) and the mollifier of nearly parallel
// edges: the product rule.
GRIP_HD inline void mollify(const Eigen::Vector3d x[4], double eps, double kappa, double b,
                            const Vector12& grad_b, const Matrix12& hess_b, bool with_hessian,
                            ContactBarrier& result) {
  const double m = edge_edge_mollifier(x[0], x[1], x[2], x[3], eps);
  result.value = kappa * m * b;
  if (m == 1.0) {
    result.gradient = kappa * grad_b;
    if (with_hessian) result.hessian = kappa * hess_b;
    return;
  }
  const Vector12 grad_m = edge_edge_mollifier_gradient(x[0], x[1], x[2], x[3], eps);
  result.gradient = kappa * (m * grad_b + b * grad_m);
  if (with_hessian) {
    const Matrix12 hess_m = edge_edge_mollifier_hessian(x[0], x[1], x[2], x[3], eps);
    result.hessian = kappa * (m * hess_b + grad_m * grad_b.transpose() +
                              grad_b * grad_m.transpose() + b * hess_m);
  }
}

}  // namespace contact_barrier_detail

// kappa m b(d) and its derivatives, with d = sqrt(s) for the squared distance s:
// db/ds = b'(d) / (2d), d2b/ds2 = (b''(d) - b'(d) / d) / (4 s). Zero beyond d_hat.
// `mollifier_eps` is the edge pair's mollifier threshold (unused for a point and a triangle).
GRIP_HD inline ContactBarrier contact_barrier(bool edge_edge, double mollifier_eps,
                                              const Eigen::Vector3d x[4], double d_hat,
                                              double kappa, bool with_hessian) {
  using namespace contact_barrier_detail;
  ContactBarrier result;
  const double s = contact_squared_distance(edge_edge, x);
  if (s >= d_hat * d_hat) return result;
  const double d = std::sqrt(s);
  const double b = barrier(d, d_hat);
  const double b1 = barrier_first_derivative(d, d_hat);
  const double db_ds = b1 / (2.0 * d);
  Vector12 grad_s;
  Matrix12 hess_s;
  squared_distance_derivatives(edge_edge, x, with_hessian, grad_s, hess_s);
  const Vector12 grad_b = db_ds * grad_s;
  Matrix12 hess_b;
  if (with_hessian) {
    const double d2b_ds2 = (barrier_second_derivative(d, d_hat) - b1 / d) / (4.0 * s);
    hess_b = d2b_ds2 * grad_s * grad_s.transpose() + db_ds * hess_s;
  }
  if (edge_edge) {
    mollify(x, mollifier_eps, kappa, b, grad_b, hess_b, with_hessian, result);
    return result;
  }
  result.value = kappa * b;
  result.gradient = kappa * grad_b;
  if (with_hessian) result.hessian = kappa * hess_b;
  return result;
}

// kappa m b(d) alone, the value contact_barrier gives, bit for bit, without the derivatives: what
// a line search needs.
GRIP_HD inline double contact_barrier_value(bool edge_edge, double mollifier_eps,
                                            const Eigen::Vector3d x[4], double d_hat,
                                            double kappa) {
  const double s = contact_squared_distance(edge_edge, x);
  if (s >= d_hat * d_hat) return 0.0;
  const double b = barrier(std::sqrt(s), d_hat);
  if (!edge_edge) return kappa * b;
  return kappa * edge_edge_mollifier(x[0], x[1], x[2], x[3], mollifier_eps) * b;
}

// kappa m |b'(d)| (N), the contact's normal force (a friction lag's lambda); 0 from d_hat on.
GRIP_HD inline double contact_normal_force(bool edge_edge, double mollifier_eps,
                                           const Eigen::Vector3d x[4], double d_hat, double kappa) {
  const double d = std::sqrt(contact_squared_distance(edge_edge, x));
  if (!(d < d_hat)) return 0.0;
  const double m = edge_edge ? edge_edge_mollifier(x[0], x[1], x[2], x[3], mollifier_eps) : 1.0;
  return -kappa * m * barrier_first_derivative(d, d_hat);
}

}  // namespace grip::solver::kernels
