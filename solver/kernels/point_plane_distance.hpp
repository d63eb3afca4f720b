#pragma once
// Squared distance from a point p to the plane through the triangle t0, t1, t2, with its
// gradient and Hessian in the stacked (p, t0, t1, t2). Requires a non-degenerate triangle.

#include <Eigen/Core>

#include "solver/kernels/derivative_maps.hpp"
#include "solver/kernels/hd.hpp"
#include "solver/kernels/spanned_plane_distance.hpp"

namespace grip::solver::kernels {

namespace detail {
// w = p - t0, a = t1 - t0, b = t2 - t0 as rows over (p, t0, t1, t2).
GRIP_HD inline Eigen::Matrix<double, 3, 4> point_plane_map() {
  Eigen::Matrix<double, 3, 4> S;
  S << 1, -1, 0, 0, 0, -1, 1, 0, 0, -1, 0, 1;
  return S;
}
}  // namespace detail

// d = ((p - t0) . n)^2 / (n . n), n = (t1 - t0) x (t2 - t0)
GRIP_HD inline double point_plane_distance_sq(const Eigen::Vector3d& p, const Eigen::Vector3d& t0,
                                              const Eigen::Vector3d& t1,
                                              const Eigen::Vector3d& t2) {
  return spanned_plane_distance_sq(p - t0, t1 - t0, t2 - t0);
}

GRIP_HD inline Eigen::Matrix<double, 12, 1> point_plane_distance_sq_gradient(
    const Eigen::Vector3d& p, const Eigen::Vector3d& t0, const Eigen::Vector3d& t1,
    const Eigen::Vector3d& t2) {
  return pull_back_gradient<3, 4>(detail::point_plane_map(),
                                  spanned_plane_distance_sq_gradient(p - t0, t1 - t0, t2 - t0));
}

GRIP_HD inline Eigen::Matrix<double, 12, 12> point_plane_distance_sq_hessian(
    const Eigen::Vector3d& p, const Eigen::Vector3d& t0, const Eigen::Vector3d& t1,
    const Eigen::Vector3d& t2) {
  return pull_back_hessian<3, 4>(detail::point_plane_map(),
                                 spanned_plane_distance_sq_hessian(p - t0, t1 - t0, t2 - t0));
}

}  // namespace grip::solver::kernels
