#pragma once
// Squared distance from a point p to the infinite line through e0, e1, with its gradient and
// Hessian in the stacked coordinates (p, e0, e1). Requires e0 != e1 (callers classify first).

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "solver/kernels/derivative_maps.hpp"
#include "solver/kernels/hd.hpp"

namespace grip::solver::kernels {

// d = ||(p - e0) x (e1 - e0)||^2 / ||e1 - e0||^2
GRIP_HD inline double point_line_distance_sq(const Eigen::Vector3d& p, const Eigen::Vector3d& e0,
                                             const Eigen::Vector3d& e1) {
  const Eigen::Vector3d e = e1 - e0;
  return (p - e0).cross(e).squaredNorm() / e.squaredNorm();
}

// With u = p - e0, e = e1 - e0, alpha = u.e / e.e and r = u - alpha e (foot point to p):
// grad = [2 r; -2 (1 - alpha) r; -2 alpha r].
GRIP_HD inline Eigen::Matrix<double, 9, 1> point_line_distance_sq_gradient(
    const Eigen::Vector3d& p, const Eigen::Vector3d& e0, const Eigen::Vector3d& e1) {
  const Eigen::Vector3d e = e1 - e0;
  const Eigen::Vector3d u = p - e0;
  const double alpha = u.dot(e) / e.squaredNorm();
  const Eigen::Vector3d r = u - alpha * e;
  Eigen::Matrix<double, 9, 1> g;
  g.segment<3>(0) = 2.0 * r;
  g.segment<3>(3) = -2.0 * (1.0 - alpha) * r;
  g.segment<3>(6) = -2.0 * alpha * r;
  return g;
}

// Hessian of d(u, e) = u.u - (u.e)^2 / e.e in (u, e), pulled back to (p, e0, e1).
GRIP_HD inline Eigen::Matrix<double, 9, 9> point_line_distance_sq_hessian(
    const Eigen::Vector3d& p, const Eigen::Vector3d& e0, const Eigen::Vector3d& e1) {
  const Eigen::Vector3d e = e1 - e0;
  const Eigen::Vector3d u = p - e0;
  const double q = e.squaredNorm();
  const double alpha = u.dot(e) / q;
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d eet = e * e.transpose() / q;
  const Eigen::Matrix3d eut = e * u.transpose() / q;

  Eigen::Matrix<double, 6, 6> h;
  h.block<3, 3>(0, 0) = 2.0 * (I - eet);
  h.block<3, 3>(0, 3) = -2.0 * (eut + alpha * I) + 4.0 * alpha * eet;
  h.block<3, 3>(3, 0) = h.block<3, 3>(0, 3).transpose();
  h.block<3, 3>(3, 3) = -2.0 * u * u.transpose() / q + 4.0 * alpha * (eut + eut.transpose()) +
                        2.0 * alpha * alpha * I - 8.0 * alpha * alpha * eet;

  Eigen::Matrix<double, 2, 3> S;  // u = p - e0, e = e1 - e0
  S << 1, -1, 0, 0, -1, 1;
  return pull_back_hessian<2, 3>(S, h);
}

}  // namespace grip::solver::kernels
