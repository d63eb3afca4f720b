#pragma once
// Squared distance from a point to the closed edge (e0, e1): classification (endpoint or
// interior) and the value, gradient and Hessian in the stacked (p, e0, e1).

#include <Eigen/Core>

#include "solver/kernels/derivative_maps.hpp"
#include "solver/kernels/distance_type.hpp"
#include "solver/kernels/hd.hpp"
#include "solver/kernels/point_line_distance.hpp"
#include "solver/kernels/point_point_distance.hpp"

namespace grip::solver::kernels {

// The foot of p on the line has parameter s = (p - e0).(e1 - e0) / |e1 - e0|^2; it is compared
// without dividing, so a zero-length edge gives P_E0.
GRIP_HD inline PointEdgeDistanceType point_edge_distance_type(const Eigen::Vector3d& p,
                                                              const Eigen::Vector3d& e0,
                                                              const Eigen::Vector3d& e1) {
  const Eigen::Vector3d e = e1 - e0;
  const double s = (p - e0).dot(e);
  if (s <= 0.0) return PointEdgeDistanceType::P_E0;
  if (s >= e.squaredNorm()) return PointEdgeDistanceType::P_E1;
  return PointEdgeDistanceType::P_E;
}

GRIP_HD inline double point_edge_distance_sq(const Eigen::Vector3d& p, const Eigen::Vector3d& e0,
                                             const Eigen::Vector3d& e1,
                                             PointEdgeDistanceType type) {
  switch (type) {
    case PointEdgeDistanceType::P_E0:
      return point_point_distance_sq(p, e0);
    case PointEdgeDistanceType::P_E1:
      return point_point_distance_sq(p, e1);
    default:
      return point_line_distance_sq(p, e0, e1);
  }
}

GRIP_HD inline double point_edge_distance_sq(const Eigen::Vector3d& p, const Eigen::Vector3d& e0,
                                             const Eigen::Vector3d& e1) {
  return point_edge_distance_sq(p, e0, e1, point_edge_distance_type(p, e0, e1));
}

GRIP_HD inline Eigen::Matrix<double, 9, 1> point_edge_distance_sq_gradient(
    const Eigen::Vector3d& p, const Eigen::Vector3d& e0, const Eigen::Vector3d& e1,
    PointEdgeDistanceType type) {
  switch (type) {
    case PointEdgeDistanceType::P_E0:
      return scatter_gradient<3, 2>(point_point_distance_sq_gradient(p, e0), {0, 1});
    case PointEdgeDistanceType::P_E1:
      return scatter_gradient<3, 2>(point_point_distance_sq_gradient(p, e1), {0, 2});
    default:
      return point_line_distance_sq_gradient(p, e0, e1);
  }
}

GRIP_HD inline Eigen::Matrix<double, 9, 1> point_edge_distance_sq_gradient(
    const Eigen::Vector3d& p, const Eigen::Vector3d& e0, const Eigen::Vector3d& e1) {
  return point_edge_distance_sq_gradient(p, e0, e1, point_edge_distance_type(p, e0, e1));
}

GRIP_HD inline Eigen::Matrix<double, 9, 9> point_edge_distance_sq_hessian(
    const Eigen::Vector3d& p, const Eigen::Vector3d& e0, const Eigen::Vector3d& e1,
    PointEdgeDistanceType type) {
  switch (type) {
    case PointEdgeDistanceType::P_E0:
      return scatter_hessian<3, 2>(point_point_distance_sq_hessian(p, e0), {0, 1});
    case PointEdgeDistanceType::P_E1:
      return scatter_hessian<3, 2>(point_point_distance_sq_hessian(p, e1), {0, 2});
    default:
      return point_line_distance_sq_hessian(p, e0, e1);
  }
}

GRIP_HD inline Eigen::Matrix<double, 9, 9> point_edge_distance_sq_hessian(
    const Eigen::Vector3d& p, const Eigen::Vector3d& e0, const Eigen::Vector3d& e1) {
  return point_edge_distance_sq_hessian(p, e0, e1, point_edge_distance_type(p, e0, e1));
}

}  // namespace grip::solver::kernels
