#pragma once
// Orthonormal bases (3x2, columns t1, t2) of the contact tangent plane for each contact type,
// computed from the lagged positions: friction acts on the relative motion projected onto them.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

#include "solver/kernels/distance_type.hpp"
#include "solver/kernels/hd.hpp"

namespace grip::solver::kernels {

// A unit vector perpendicular to v != 0: v crossed with the coordinate axis least aligned with it
// (|v x axis| >= |v| sqrt(2/3), so the normalization is always well conditioned).
GRIP_HD inline Eigen::Vector3d perpendicular_unit(const Eigen::Vector3d& v) {
  const Eigen::Vector3d m = v.cwiseAbs();
  const Eigen::Vector3d axis = (m.x() <= m.y() && m.x() <= m.z()) ? Eigen::Vector3d::UnitX()
                               : (m.y() <= m.z())                 ? Eigen::Vector3d::UnitY()
                                                                  : Eigen::Vector3d::UnitZ();
  return v.cross(axis).normalized();
}

namespace detail {
// Basis [t1, c / |c|] for a unit tangent t1 and a vector c perpendicular to it. When
// |c|^2 <= kParallelSinSq * scale_sq the direction of c is round-off (the contact normal is
// undefined there), and any unit vector perpendicular to t1 completes the basis instead.
GRIP_HD inline Eigen::Matrix<double, 3, 2> basis_from(const Eigen::Vector3d& t1,
                                                      const Eigen::Vector3d& c, double scale_sq) {
  Eigen::Matrix<double, 3, 2> basis;
  basis.col(0) = t1;
  const double cc = c.squaredNorm();
  basis.col(1) = (cc > kParallelSinSq * scale_sq) ? Eigen::Vector3d(c / std::sqrt(cc))
                                                  : perpendicular_unit(t1);
  return basis;
}
}  // namespace detail

// Normal p0 - p1 (p0 != p1); t1 = any unit perpendicular, t2 = normal x t1 normalized.
GRIP_HD inline Eigen::Matrix<double, 3, 2> point_point_tangent_basis(const Eigen::Vector3d& p0,
                                                                     const Eigen::Vector3d& p1) {
  const Eigen::Vector3d n = p0 - p1;
  const Eigen::Vector3d t1 = perpendicular_unit(n);
  Eigen::Matrix<double, 3, 2> basis;
  basis << t1, n.cross(t1).normalized();
  return basis;
}

// t1 along the edge, t2 = e x (p - e0) normalized (perpendicular to the edge and the normal).
GRIP_HD inline Eigen::Matrix<double, 3, 2> point_edge_tangent_basis(const Eigen::Vector3d& p,
                                                                    const Eigen::Vector3d& e0,
                                                                    const Eigen::Vector3d& e1) {
  const Eigen::Vector3d e = e1 - e0;
  const Eigen::Vector3d u = p - e0;
  return detail::basis_from(e.normalized(), e.normalized().cross(u), u.squaredNorm());
}

// The triangle's plane: t1 along t0t1, t2 = n x t1 with n the face normal.
GRIP_HD inline Eigen::Matrix<double, 3, 2> point_triangle_tangent_basis(
    const Eigen::Vector3d& /*p*/, const Eigen::Vector3d& t0, const Eigen::Vector3d& t1,
    const Eigen::Vector3d& t2) {
  const Eigen::Vector3d a = (t1 - t0).normalized();
  const Eigen::Vector3d b = t2 - t0;
  return detail::basis_from(a, a.cross(b).cross(a), b.squaredNorm());
}

// The plane parallel to both edges: t1 along edge a, t2 = n x t1 with n = a x b.
GRIP_HD inline Eigen::Matrix<double, 3, 2> edge_edge_tangent_basis(const Eigen::Vector3d& ea0,
                                                                   const Eigen::Vector3d& ea1,
                                                                   const Eigen::Vector3d& eb0,
                                                                   const Eigen::Vector3d& eb1) {
  const Eigen::Vector3d a = (ea1 - ea0).normalized();
  const Eigen::Vector3d b = eb1 - eb0;
  return detail::basis_from(a, a.cross(b).cross(a), b.squaredNorm());
}

}  // namespace grip::solver::kernels
