#pragma once
// Squared distance from the vector w to the plane through the origin spanned by a and b,
// d = (w . n)^2 / (n . n) with n = a x b, and its derivatives in the stacked (w, a, b).
// Point-plane and line-line distances are this function of vertex differences.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "solver/kernels/derivative_maps.hpp"
#include "solver/kernels/hd.hpp"

namespace grip::solver::kernels {

GRIP_HD inline double spanned_plane_distance_sq(const Eigen::Vector3d& w, const Eigen::Vector3d& a,
                                                const Eigen::Vector3d& b) {
  const Eigen::Vector3d n = a.cross(b);
  const double g = w.dot(n);
  return g * g / n.squaredNorm();
}

namespace detail {

// First derivatives of g = w . (a x b) and q = ||a x b||^2 in (w, a, b).
struct SpannedPlaneTerms {
  double g, q;
  Eigen::Matrix<double, 9, 1> dg, dq;
};

GRIP_HD inline SpannedPlaneTerms spanned_plane_terms(const Eigen::Vector3d& w,
                                                     const Eigen::Vector3d& a,
                                                     const Eigen::Vector3d& b) {
  SpannedPlaneTerms t;
  const Eigen::Vector3d n = a.cross(b);
  t.g = w.dot(n);
  t.q = n.squaredNorm();
  t.dg << n, b.cross(w), w.cross(a);
  const double ab = a.dot(b);
  t.dq << Eigen::Vector3d::Zero(), 2.0 * (b.squaredNorm() * a - ab * b),
      2.0 * (a.squaredNorm() * b - ab * a);
  return t;
}

}  // namespace detail

// grad d = (2 g / q) grad g - (g^2 / q^2) grad q
GRIP_HD inline Eigen::Matrix<double, 9, 1> spanned_plane_distance_sq_gradient(
    const Eigen::Vector3d& w, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const detail::SpannedPlaneTerms t = detail::spanned_plane_terms(w, a, b);
  return (2.0 * t.g / t.q) * t.dg - (t.g * t.g / (t.q * t.q)) * t.dq;
}

// hess d = 2/q dg dg^T + 2g/q hess g - 2g/q^2 (dg dq^T + dq dg^T) - g^2/q^2 hess q
//          + 2 g^2/q^3 dq dq^T, with g trilinear (hess g made of cross matrices) and
// q = |a|^2 |b|^2 - (a.b)^2.
GRIP_HD inline Eigen::Matrix<double, 9, 9> spanned_plane_distance_sq_hessian(
    const Eigen::Vector3d& w, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const detail::SpannedPlaneTerms t = detail::spanned_plane_terms(w, a, b);
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();

  Eigen::Matrix<double, 9, 9> hg = Eigen::Matrix<double, 9, 9>::Zero();
  hg.block<3, 3>(0, 3) = -cross_matrix(b);
  hg.block<3, 3>(0, 6) = cross_matrix(a);
  hg.block<3, 3>(3, 6) = -cross_matrix(w);
  hg.block<3, 3>(3, 0) = hg.block<3, 3>(0, 3).transpose();
  hg.block<3, 3>(6, 0) = hg.block<3, 3>(0, 6).transpose();
  hg.block<3, 3>(6, 3) = hg.block<3, 3>(3, 6).transpose();

  Eigen::Matrix<double, 9, 9> hq = Eigen::Matrix<double, 9, 9>::Zero();
  const double ab = a.dot(b);
  hq.block<3, 3>(3, 3) = 2.0 * (b.squaredNorm() * I - b * b.transpose());
  hq.block<3, 3>(6, 6) = 2.0 * (a.squaredNorm() * I - a * a.transpose());
  hq.block<3, 3>(3, 6) = 4.0 * a * b.transpose() - 2.0 * b * a.transpose() - 2.0 * ab * I;
  hq.block<3, 3>(6, 3) = hq.block<3, 3>(3, 6).transpose();

  const double g = t.g, q = t.q;
  const Eigen::Matrix<double, 9, 9> cross_terms = t.dg * t.dq.transpose() + t.dq * t.dg.transpose();
  return (2.0 / q) * t.dg * t.dg.transpose() + (2.0 * g / q) * hg -
         (2.0 * g / (q * q)) * cross_terms - (g * g / (q * q)) * hq +
         (2.0 * g * g / (q * q * q)) * t.dq * t.dq.transpose();
}

}  // namespace grip::solver::kernels
