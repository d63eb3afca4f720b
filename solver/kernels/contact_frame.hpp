#pragma once
// The lagged friction frame of one contact pair: the weights of its four vertices in the
// relative displacement of the two closest points (u = sum_i w_i dx_i, the first side positive)
// and an orthonormal tangent basis perpendicular to the line between the closest points. Both
// follow the pair's distance type, so a point nearest a triangle's edge or vertex gets that
// edge's or vertex's weights.
#include <Eigen/Core>

#include "solver/kernels/closest_point.hpp"
#include "solver/kernels/distance.hpp"
#include "solver/kernels/hd.hpp"
#include "solver/kernels/tangent_basis.hpp"

namespace grip::solver::kernels {

struct ContactFrame {
  double weight[4];
  Eigen::Matrix<double, 3, 2> basis;

  // T_k = Gamma^T basis (12 x 2): u = T_k^T dx for the pair's stacked vertex displacements.
  GRIP_HD Eigen::Matrix<double, 12, 2> tangent_operator() const {
    Eigen::Matrix<double, 12, 2> t;
    for (int i = 0; i < 4; ++i) t.block<3, 2>(3 * i, 0) = weight[i] * basis;
    return t;
  }
};

namespace contact_frame_detail {

GRIP_HD inline double clamp01(double s) { return s < 0.0 ? 0.0 : (s > 1.0 ? 1.0 : s); }

// Parameter of the closest point of segment e0e1 to p.
GRIP_HD inline double segment_parameter(const Eigen::Vector3d& p, const Eigen::Vector3d& e0,
                                        const Eigen::Vector3d& e1) {
  return clamp01(point_edge_closest_point(p, e0, e1));
}

GRIP_HD inline ContactFrame with_basis(ContactFrame frame, const Eigen::Vector3d x[4]) {
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (int i = 0; i < 4; ++i) normal += frame.weight[i] * x[i];
  const Eigen::Vector3d t1 = perpendicular_unit(normal);
  frame.basis.col(0) = t1;
  frame.basis.col(1) = normal.cross(t1).normalized();
  return frame;
}

}  // namespace contact_frame_detail

GRIP_HD inline ContactFrame point_triangle_frame(const Eigen::Vector3d x[4]) {
  using T = PointTriangleDistanceType;
  using contact_frame_detail::segment_parameter;
  ContactFrame f{{1.0, 0.0, 0.0, 0.0}, Eigen::Matrix<double, 3, 2>::Zero()};
  // The triangle's weights are negative: u is the point's motion relative to the triangle's.
  switch (point_triangle_distance_type(x[0], x[1], x[2], x[3])) {
    case T::P_T0:
      f.weight[1] = -1.0;
      break;
    case T::P_T1:
      f.weight[2] = -1.0;
      break;
    case T::P_T2:
      f.weight[3] = -1.0;
      break;
    case T::P_E0: {
      const double s = segment_parameter(x[0], x[1], x[2]);
      f.weight[1] = -(1.0 - s), f.weight[2] = -s;
      break;
    }
    case T::P_E1: {
      const double s = segment_parameter(x[0], x[2], x[3]);
      f.weight[2] = -(1.0 - s), f.weight[3] = -s;
      break;
    }
    case T::P_E2: {
      const double s = segment_parameter(x[0], x[3], x[1]);
      f.weight[3] = -(1.0 - s), f.weight[1] = -s;
      break;
    }
    case T::P_T: {
      const Eigen::Vector2d b = point_triangle_closest_point(x[0], x[1], x[2], x[3]);
      f.weight[1] = -(1.0 - b[0] - b[1]), f.weight[2] = -b[0], f.weight[3] = -b[1];
      break;
    }
  }
  return contact_frame_detail::with_basis(f, x);
}

GRIP_HD inline ContactFrame edge_edge_frame(const Eigen::Vector3d x[4]) {
  using T = EdgeEdgeDistanceType;
  using contact_frame_detail::segment_parameter;
  double a = 0.0, b = 0.0;  // closest points ea0 + a (ea1 - ea0) and eb0 + b (eb1 - eb0)
  switch (edge_edge_distance_type(x[0], x[1], x[2], x[3])) {
    case T::EA0_EB0:
      break;
    case T::EA0_EB1:
      b = 1.0;
      break;
    case T::EA1_EB0:
      a = 1.0;
      break;
    case T::EA1_EB1:
      a = 1.0, b = 1.0;
      break;
    case T::EA_EB0:
      a = segment_parameter(x[2], x[0], x[1]);
      break;
    case T::EA_EB1:
      a = segment_parameter(x[3], x[0], x[1]), b = 1.0;
      break;
    case T::EA0_EB:
      b = segment_parameter(x[0], x[2], x[3]);
      break;
    case T::EA1_EB:
      a = 1.0, b = segment_parameter(x[1], x[2], x[3]);
      break;
    case T::EA_EB: {
      const Eigen::Vector2d ab = edge_edge_closest_point(x[0], x[1], x[2], x[3]);
      a = ab[0], b = ab[1];
      break;
    }
  }
  ContactFrame f{{1.0 - a, a, -(1.0 - b), -b}, Eigen::Matrix<double, 3, 2>::Zero()};
  return contact_frame_detail::with_basis(f, x);
}

}  // namespace grip::solver::kernels
