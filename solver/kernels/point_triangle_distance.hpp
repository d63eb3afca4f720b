#pragma once
// Squared distance from a point to the closed triangle (t0, t1, t2): classification (vertex,
// edge or face) and the value, gradient and Hessian in the stacked (p, t0, t1, t2).

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "solver/kernels/derivative_maps.hpp"
#include "solver/kernels/distance_type.hpp"
#include "solver/kernels/hd.hpp"
#include "solver/kernels/point_edge_distance.hpp"
#include "solver/kernels/point_plane_distance.hpp"
#include "solver/kernels/point_point_distance.hpp"

namespace grip::solver::kernels {

// The face is closest iff p projects strictly inside the triangle (tested with signs of triple
// products, no division); otherwise the nearest of the three closed edges is. A degenerate
// triangle (sin^2 of the angle at t0 below kParallelSinSq) has no usable normal and always takes
// the edge branch. Ties go to the first edge in the order t0t1, t1t2, t2t0.
GRIP_HD inline PointTriangleDistanceType point_triangle_distance_type(const Eigen::Vector3d& p,
                                                                      const Eigen::Vector3d& t0,
                                                                      const Eigen::Vector3d& t1,
                                                                      const Eigen::Vector3d& t2) {
  using T = PointTriangleDistanceType;
  const Eigen::Vector3d a = t1 - t0, b = t2 - t0;
  const Eigen::Vector3d n = a.cross(b);
  if (n.squaredNorm() > kParallelSinSq * a.squaredNorm() * b.squaredNorm() &&
      n.dot(a.cross(p - t0)) > 0.0 && n.dot((t2 - t1).cross(p - t1)) > 0.0 &&
      n.dot((t0 - t2).cross(p - t2)) > 0.0)
    return T::P_T;

  // Edge k runs from vertex k to vertex k+1; its endpoint types map to the triangle's vertices.
  const Eigen::Vector3d* v[3] = {&t0, &t1, &t2};
  constexpr T kVertex[3] = {T::P_T0, T::P_T1, T::P_T2};
  constexpr T kEdge[3] = {T::P_E0, T::P_E1, T::P_E2};
  T best = T::P_T0;
  double best_d = 0.0;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d& e0 = *v[k];
    const Eigen::Vector3d& e1 = *v[(k + 1) % 3];
    const PointEdgeDistanceType pe = point_edge_distance_type(p, e0, e1);
    const double d = point_edge_distance_sq(p, e0, e1, pe);
    if (k == 0 || d < best_d) {
      best_d = d;
      best = pe == PointEdgeDistanceType::P_E0   ? kVertex[k]
             : pe == PointEdgeDistanceType::P_E1 ? kVertex[(k + 1) % 3]
                                                 : kEdge[k];
    }
  }
  return best;
}

GRIP_HD inline double point_triangle_distance_sq(const Eigen::Vector3d& p,
                                                 const Eigen::Vector3d& t0,
                                                 const Eigen::Vector3d& t1,
                                                 const Eigen::Vector3d& t2,
                                                 PointTriangleDistanceType type) {
  using T = PointTriangleDistanceType;
  switch (type) {
    case T::P_T0:
      return point_point_distance_sq(p, t0);
    case T::P_T1:
      return point_point_distance_sq(p, t1);
    case T::P_T2:
      return point_point_distance_sq(p, t2);
    case T::P_E0:
      return point_line_distance_sq(p, t0, t1);
    case T::P_E1:
      return point_line_distance_sq(p, t1, t2);
    case T::P_E2:
      return point_line_distance_sq(p, t2, t0);
    default:
      return point_plane_distance_sq(p, t0, t1, t2);
  }
}

GRIP_HD inline double point_triangle_distance_sq(const Eigen::Vector3d& p,
                                                 const Eigen::Vector3d& t0,
                                                 const Eigen::Vector3d& t1,
                                                 const Eigen::Vector3d& t2) {
  return point_triangle_distance_sq(p, t0, t1, t2, point_triangle_distance_type(p, t0, t1, t2));
}

GRIP_HD inline Eigen::Matrix<double, 12, 1> point_triangle_distance_sq_gradient(
    const Eigen::Vector3d& p, const Eigen::Vector3d& t0, const Eigen::Vector3d& t1,
    const Eigen::Vector3d& t2, PointTriangleDistanceType type) {
  using T = PointTriangleDistanceType;
  switch (type) {
    case T::P_T0:
      return scatter_gradient<4, 2>(point_point_distance_sq_gradient(p, t0), {0, 1});
    case T::P_T1:
      return scatter_gradient<4, 2>(point_point_distance_sq_gradient(p, t1), {0, 2});
    case T::P_T2:
      return scatter_gradient<4, 2>(point_point_distance_sq_gradient(p, t2), {0, 3});
    case T::P_E0:
      return scatter_gradient<4, 3>(point_line_distance_sq_gradient(p, t0, t1), {0, 1, 2});
    case T::P_E1:
      return scatter_gradient<4, 3>(point_line_distance_sq_gradient(p, t1, t2), {0, 2, 3});
    case T::P_E2:
      return scatter_gradient<4, 3>(point_line_distance_sq_gradient(p, t2, t0), {0, 3, 1});
    default:
      return point_plane_distance_sq_gradient(p, t0, t1, t2);
  }
}

GRIP_HD inline Eigen::Matrix<double, 12, 1> point_triangle_distance_sq_gradient(
    const Eigen::Vector3d& p, const Eigen::Vector3d& t0, const Eigen::Vector3d& t1,
    const Eigen::Vector3d& t2) {
  return point_triangle_distance_sq_gradient(p, t0, t1, t2,
                                             point_triangle_distance_type(p, t0, t1, t2));
}

GRIP_HD inline Eigen::Matrix<double, 12, 12> point_triangle_distance_sq_hessian(
    const Eigen::Vector3d& p, const Eigen::Vector3d& t0, const Eigen::Vector3d& t1,
    const Eigen::Vector3d& t2, PointTriangleDistanceType type) {
  using T = PointTriangleDistanceType;
  switch (type) {
    case T::P_T0:
      return scatter_hessian<4, 2>(point_point_distance_sq_hessian(p, t0), {0, 1});
    case T::P_T1:
      return scatter_hessian<4, 2>(point_point_distance_sq_hessian(p, t1), {0, 2});
    case T::P_T2:
      return scatter_hessian<4, 2>(point_point_distance_sq_hessian(p, t2), {0, 3});
    case T::P_E0:
      return scatter_hessian<4, 3>(point_line_distance_sq_hessian(p, t0, t1), {0, 1, 2});
    case T::P_E1:
      return scatter_hessian<4, 3>(point_line_distance_sq_hessian(p, t1, t2), {0, 2, 3});
    case T::P_E2:
      return scatter_hessian<4, 3>(point_line_distance_sq_hessian(p, t2, t0), {0, 3, 1});
    default:
      return point_plane_distance_sq_hessian(p, t0, t1, t2);
  }
}

GRIP_HD inline Eigen::Matrix<double, 12, 12> point_triangle_distance_sq_hessian(
    const Eigen::Vector3d& p, const Eigen::Vector3d& t0, const Eigen::Vector3d& t1,
    const Eigen::Vector3d& t2) {
  return point_triangle_distance_sq_hessian(p, t0, t1, t2,
                                            point_triangle_distance_type(p, t0, t1, t2));
}

}  // namespace grip::solver::kernels
