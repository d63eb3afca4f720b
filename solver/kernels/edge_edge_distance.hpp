#pragma once
// Squared distance between the closed edges (ea0, ea1) and (eb0, eb1): classification and the
// value, gradient and Hessian in the stacked (ea0, ea1, eb0, eb1).

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "solver/kernels/derivative_maps.hpp"
#include "solver/kernels/distance_type.hpp"
#include "solver/kernels/hd.hpp"
#include "solver/kernels/line_line_distance.hpp"
#include "solver/kernels/point_edge_distance.hpp"
#include "solver/kernels/point_line_distance.hpp"
#include "solver/kernels/point_point_distance.hpp"

namespace grip::solver::kernels {

// |ea0 + s a - (eb0 + t b)|^2 is a convex quadratic on [0,1]^2: if its unconstrained minimizer is
// strictly inside the square the lines' common perpendicular is the answer (EA_EB); otherwise the
// minimum lies on the square's boundary, i.e. it is the nearest of the four endpoint-to-edge
// distances. Parallel edges (sin^2 below kParallelSinSq) have no unique perpendicular and always
// take the boundary branch, which is exact for them. Ties go to the first candidate in the
// order ea0-eb, ea1-eb, eb0-ea, eb1-ea.
GRIP_HD inline EdgeEdgeDistanceType edge_edge_distance_type(const Eigen::Vector3d& ea0,
                                                            const Eigen::Vector3d& ea1,
                                                            const Eigen::Vector3d& eb0,
                                                            const Eigen::Vector3d& eb1) {
  using T = EdgeEdgeDistanceType;
  using PE = PointEdgeDistanceType;
  const Eigen::Vector3d a = ea1 - ea0, b = eb1 - eb0, w = ea0 - eb0;
  const double aa = a.squaredNorm(), bb = b.squaredNorm(), ab = a.dot(b);
  const double den = a.cross(b).squaredNorm();
  if (den > kParallelSinSq * aa * bb) {
    const double aw = a.dot(w), bw = b.dot(w);
    const double s_num = ab * bw - bb * aw;  // s = s_num / den along a
    const double t_num = aa * bw - ab * aw;  // t = t_num / den along b
    if (s_num > 0.0 && s_num < den && t_num > 0.0 && t_num < den) return T::EA_EB;
  }

  // Candidate k: point, edge, and the edge-edge types for the point-edge results P_E0, P_E1, P_E.
  const Eigen::Vector3d* point[4] = {&ea0, &ea1, &eb0, &eb1};
  const Eigen::Vector3d* edge0[4] = {&eb0, &eb0, &ea0, &ea0};
  const Eigen::Vector3d* edge1[4] = {&eb1, &eb1, &ea1, &ea1};
  constexpr T kType[4][3] = {{T::EA0_EB0, T::EA0_EB1, T::EA0_EB},
                             {T::EA1_EB0, T::EA1_EB1, T::EA1_EB},
                             {T::EA0_EB0, T::EA1_EB0, T::EA_EB0},
                             {T::EA0_EB1, T::EA1_EB1, T::EA_EB1}};
  T best = T::EA0_EB0;
  double best_d = 0.0;
  for (int k = 0; k < 4; ++k) {
    const PE pe = point_edge_distance_type(*point[k], *edge0[k], *edge1[k]);
    const double d = point_edge_distance_sq(*point[k], *edge0[k], *edge1[k], pe);
    if (k == 0 || d < best_d) {
      best_d = d;
      best = kType[k][pe == PE::P_E0 ? 0 : pe == PE::P_E1 ? 1 : 2];
    }
  }
  return best;
}

GRIP_HD inline double edge_edge_distance_sq(const Eigen::Vector3d& ea0, const Eigen::Vector3d& ea1,
                                            const Eigen::Vector3d& eb0, const Eigen::Vector3d& eb1,
                                            EdgeEdgeDistanceType type) {
  using T = EdgeEdgeDistanceType;
  switch (type) {
    case T::EA0_EB0:
      return point_point_distance_sq(ea0, eb0);
    case T::EA0_EB1:
      return point_point_distance_sq(ea0, eb1);
    case T::EA1_EB0:
      return point_point_distance_sq(ea1, eb0);
    case T::EA1_EB1:
      return point_point_distance_sq(ea1, eb1);
    case T::EA_EB0:
      return point_line_distance_sq(eb0, ea0, ea1);
    case T::EA_EB1:
      return point_line_distance_sq(eb1, ea0, ea1);
    case T::EA0_EB:
      return point_line_distance_sq(ea0, eb0, eb1);
    case T::EA1_EB:
      return point_line_distance_sq(ea1, eb0, eb1);
    default:
      return line_line_distance_sq(ea0, ea1, eb0, eb1);
  }
}

GRIP_HD inline double edge_edge_distance_sq(const Eigen::Vector3d& ea0, const Eigen::Vector3d& ea1,
                                            const Eigen::Vector3d& eb0,
                                            const Eigen::Vector3d& eb1) {
  return edge_edge_distance_sq(ea0, ea1, eb0, eb1, edge_edge_distance_type(ea0, ea1, eb0, eb1));
}

GRIP_HD inline Eigen::Matrix<double, 12, 1> edge_edge_distance_sq_gradient(
    const Eigen::Vector3d& ea0, const Eigen::Vector3d& ea1, const Eigen::Vector3d& eb0,
    const Eigen::Vector3d& eb1, EdgeEdgeDistanceType type) {
  using T = EdgeEdgeDistanceType;
  switch (type) {
    case T::EA0_EB0:
      return scatter_gradient<4, 2>(point_point_distance_sq_gradient(ea0, eb0), {0, 2});
    case T::EA0_EB1:
      return scatter_gradient<4, 2>(point_point_distance_sq_gradient(ea0, eb1), {0, 3});
    case T::EA1_EB0:
      return scatter_gradient<4, 2>(point_point_distance_sq_gradient(ea1, eb0), {1, 2});
    case T::EA1_EB1:
      return scatter_gradient<4, 2>(point_point_distance_sq_gradient(ea1, eb1), {1, 3});
    case T::EA_EB0:
      return scatter_gradient<4, 3>(point_line_distance_sq_gradient(eb0, ea0, ea1), {2, 0, 1});
    case T::EA_EB1:
      return scatter_gradient<4, 3>(point_line_distance_sq_gradient(eb1, ea0, ea1), {3, 0, 1});
    case T::EA0_EB:
      return scatter_gradient<4, 3>(point_line_distance_sq_gradient(ea0, eb0, eb1), {0, 2, 3});
    case T::EA1_EB:
      return scatter_gradient<4, 3>(point_line_distance_sq_gradient(ea1, eb0, eb1), {1, 2, 3});
    default:
      return line_line_distance_sq_gradient(ea0, ea1, eb0, eb1);
  }
}

GRIP_HD inline Eigen::Matrix<double, 12, 1> edge_edge_distance_sq_gradient(
    const Eigen::Vector3d& ea0, const Eigen::Vector3d& ea1, const Eigen::Vector3d& eb0,
    const Eigen::Vector3d& eb1) {
  return edge_edge_distance_sq_gradient(ea0, ea1, eb0, eb1,
                                        edge_edge_distance_type(ea0, ea1, eb0, eb1));
}

GRIP_HD inline Eigen::Matrix<double, 12, 12> edge_edge_distance_sq_hessian(
    const Eigen::Vector3d& ea0, const Eigen::Vector3d& ea1, const Eigen::Vector3d& eb0,
    const Eigen::Vector3d& eb1, EdgeEdgeDistanceType type) {
  using T = EdgeEdgeDistanceType;
  switch (type) {
    case T::EA0_EB0:
      return scatter_hessian<4, 2>(point_point_distance_sq_hessian(ea0, eb0), {0, 2});
    case T::EA0_EB1:
      return scatter_hessian<4, 2>(point_point_distance_sq_hessian(ea0, eb1), {0, 3});
    case T::EA1_EB0:
      return scatter_hessian<4, 2>(point_point_distance_sq_hessian(ea1, eb0), {1, 2});
    case T::EA1_EB1:
      return scatter_hessian<4, 2>(point_point_distance_sq_hessian(ea1, eb1), {1, 3});
    case T::EA_EB0:
      return scatter_hessian<4, 3>(point_line_distance_sq_hessian(eb0, ea0, ea1), {2, 0, 1});
    case T::EA_EB1:
      return scatter_hessian<4, 3>(point_line_distance_sq_hessian(eb1, ea0, ea1), {3, 0, 1});
    case T::EA0_EB:
      return scatter_hessian<4, 3>(point_line_distance_sq_hessian(ea0, eb0, eb1), {0, 2, 3});
    case T::EA1_EB:
      return scatter_hessian<4, 3>(point_line_distance_sq_hessian(ea1, eb0, eb1), {1, 2, 3});
    default:
      return line_line_distance_sq_hessian(ea0, ea1, eb0, eb1);
  }
}

GRIP_HD inline Eigen::Matrix<double, 12, 12> edge_edge_distance_sq_hessian(
    const Eigen::Vector3d& ea0, const Eigen::Vector3d& ea1, const Eigen::Vector3d& eb0,
    const Eigen::Vector3d& eb1) {
  return edge_edge_distance_sq_hessian(ea0, ea1, eb0, eb1,
                                       edge_edge_distance_type(ea0, ea1, eb0, eb1));
}

}  // namespace grip::solver::kernels
