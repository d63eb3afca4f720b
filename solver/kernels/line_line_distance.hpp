#pragma once
// Squared distance between the infinite lines through ea0, ea1 and eb0, eb1, with its gradient
// and Hessian in the stacked (ea0, ea1, eb0, eb1). Requires non-parallel lines.

#include <Eigen/Core>

#include "solver/kernels/derivative_maps.hpp"
#include "solver/kernels/hd.hpp"
#include "solver/kernels/spanned_plane_distance.hpp"

namespace grip::solver::kernels {

namespace detail {
// w = eb0 - ea0, a = ea1 - ea0, b = eb1 - eb0 as rows over (ea0, ea1, eb0, eb1).
GRIP_HD inline Eigen::Matrix<double, 3, 4> line_line_map() {
  Eigen::Matrix<double, 3, 4> S;
  S << -1, 0, 1, 0, -1, 1, 0, 0, 0, 0, -1, 1;
  return S;
}
}  // namespace detail

// d = ((eb0 - ea0) . n)^2 / (n . n), n = (ea1 - ea0) x (eb1 - eb0)
GRIP_HD inline double line_line_distance_sq(const Eigen::Vector3d& ea0, const Eigen::Vector3d& ea1,
                                            const Eigen::Vector3d& eb0,
                                            const Eigen::Vector3d& eb1) {
  return spanned_plane_distance_sq(eb0 - ea0, ea1 - ea0, eb1 - eb0);
}

GRIP_HD inline Eigen::Matrix<double, 12, 1> line_line_distance_sq_gradient(
    const Eigen::Vector3d& ea0, const Eigen::Vector3d& ea1, const Eigen::Vector3d& eb0,
    const Eigen::Vector3d& eb1) {
  return pull_back_gradient<3, 4>(
      detail::line_line_map(), spanned_plane_distance_sq_gradient(eb0 - ea0, ea1 - ea0, eb1 - eb0));
}

GRIP_HD inline Eigen::Matrix<double, 12, 12> line_line_distance_sq_hessian(
    const Eigen::Vector3d& ea0, const Eigen::Vector3d& ea1, const Eigen::Vector3d& eb0,
    const Eigen::Vector3d& eb1) {
  return pull_back_hessian<3, 4>(
      detail::line_line_map(), spanned_plane_distance_sq_hessian(eb0 - ea0, ea1 - ea0, eb1 - eb0));
}

}  // namespace grip::solver::kernels
