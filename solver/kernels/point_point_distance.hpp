#pragma once
// Squared distance between two points, d = ||p0 - p1||^2, with its gradient and Hessian
// with respect to the stacked coordinates (p0, p1).

#include <Eigen/Core>

#include "solver/kernels/hd.hpp"

namespace grip::solver::kernels {

GRIP_HD inline double point_point_distance_sq(const Eigen::Vector3d& p0,
                                              const Eigen::Vector3d& p1) {
  return (p0 - p1).squaredNorm();
}

// [2 (p0 - p1); -2 (p0 - p1)]
GRIP_HD inline Eigen::Matrix<double, 6, 1> point_point_distance_sq_gradient(
    const Eigen::Vector3d& p0, const Eigen::Vector3d& p1) {
  Eigen::Matrix<double, 6, 1> g;
  g.head<3>() = 2.0 * (p0 - p1);
  g.tail<3>() = -g.head<3>();
  return g;
}

// [[2I, -2I], [-2I, 2I]], independent of the positions.
GRIP_HD inline Eigen::Matrix<double, 6, 6> point_point_distance_sq_hessian(
    const Eigen::Vector3d& /*p0*/, const Eigen::Vector3d& /*p1*/) {
  Eigen::Matrix<double, 6, 6> h;
  const Eigen::Matrix3d i2 = 2.0 * Eigen::Matrix3d::Identity();
  h << i2, -i2, -i2, i2;
  return h;
}

}  // namespace grip::solver::kernels
