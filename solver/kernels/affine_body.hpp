#pragma once
// Affine body (ABD, Lan et al. 2022) kinematics and orthogonality potential: a stiff body's
// 12 DOFs q, the world position of a rest-space point and its 3x12 Jacobian, and
// kappa V ||A A^T - I||_F^2 with its gradient and Hessian (its PSD projection is the caller's:
// psd_projection.hpp on the host, jacobi_psd_projection.hpp on a device).
//
// DOF layout: q = (p, a1, a2, a3), where p is the translation and a_i are the ROWS of the
// 3x3 affine matrix A, so that x = A xbar + p, i.e. x_i = p_i + a_i . xbar.
#include <Eigen/Core>

#include "solver/kernels/hd.hpp"

namespace grip::solver::kernels {

using Vector12d = Eigen::Matrix<double, 12, 1>;
using Matrix12d = Eigen::Matrix<double, 12, 12>;

// The affine matrix A of q (rows a1, a2, a3).
GRIP_HD inline Eigen::Matrix3d affine_body_matrix(const Vector12d& q) {
  Eigen::Matrix3d a;
  for (int i = 0; i < 3; ++i) a.row(i) = q.segment<3>(3 + 3 * i).transpose();
  return a;
}

// q of the affine map x = A xbar + p (the identity map is q = (0, e1, e2, e3)).
GRIP_HD inline Vector12d affine_body_dofs(const Eigen::Matrix3d& a, const Eigen::Vector3d& p) {
  Vector12d q;
  q.segment<3>(0) = p;
  for (int i = 0; i < 3; ++i) q.segment<3>(3 + 3 * i) = a.row(i).transpose();
  return q;
}

// World position x = A xbar + p of the rest-space point xbar.
GRIP_HD inline Eigen::Vector3d affine_body_position(const Vector12d& q,
                                                    const Eigen::Vector3d& rest_point) {
  return affine_body_matrix(q) * rest_point + q.segment<3>(0);
}

// J(xbar) = dx/dq = [I3 | diag(xbar^T, xbar^T, xbar^T)]; x = J(xbar) q. Constant in q.
GRIP_HD inline Eigen::Matrix<double, 3, 12> affine_body_jacobian(
    const Eigen::Vector3d& rest_point) {
  Eigen::Matrix<double, 3, 12> j = Eigen::Matrix<double, 3, 12>::Zero();
  j.block<3, 3>(0, 0).setIdentity();
  for (int i = 0; i < 3; ++i) j.block<1, 3>(i, 3 + 3 * i) = rest_point.transpose();
  return j;
}

// V_perp(q) = stiffness * volume * ||A A^T - I||_F^2 (stiffness kappa in Pa, volume in m^3).
// Zero exactly when A is orthogonal (any rotation or reflection), whatever p is.
GRIP_HD inline double affine_body_orthogonality_energy(const Vector12d& q, double stiffness,
                                                       double volume) {
  const Eigen::Matrix3d a = affine_body_matrix(q);
  return stiffness * volume * (a * a.transpose() - Eigen::Matrix3d::Identity()).squaredNorm();
}

// dV_perp/da_i = 4 kappa V (A^T A - I) a_i; dV_perp/dp = 0.
GRIP_HD inline Vector12d affine_body_orthogonality_gradient(const Vector12d& q, double stiffness,
                                                            double volume) {
  const Eigen::Matrix3d a = affine_body_matrix(q);
  const Eigen::Matrix3d m = a.transpose() * a - Eigen::Matrix3d::Identity();
  Vector12d g = Vector12d::Zero();
  for (int i = 0; i < 3; ++i) {
    g.segment<3>(3 + 3 * i) = 4.0 * stiffness * volume * m * q.segment<3>(3 + 3 * i);
  }
  return g;
}

// d^2 V_perp / da_i da_j = 4 kappa V (delta_ij (A^T A - I) + a_j a_i^T + (a_i . a_j) I): the 9x9
// block of the Hessian in (a1, a2, a3), its only nonzero part (the translation's rows and
// columns are zero). Not projected: device code projects it by Jacobi rotations
// (jacobi_psd_projection.hpp).
GRIP_HD inline Eigen::Matrix<double, 9, 9> affine_body_orthogonality_block(const Vector12d& q,
                                                                           double stiffness,
                                                                           double volume) {
  const Eigen::Matrix3d a = affine_body_matrix(q);
  const Eigen::Matrix3d m = a.transpose() * a - Eigen::Matrix3d::Identity();
  Eigen::Matrix<double, 9, 9> block;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d ai = q.segment<3>(3 + 3 * i);
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d aj = q.segment<3>(3 + 3 * j);
      Eigen::Matrix3d b = aj * ai.transpose() + ai.dot(aj) * Eigen::Matrix3d::Identity();
      if (i == j) b += m;
      block.block<3, 3>(3 * i, 3 * j) = 4.0 * stiffness * volume * b;
    }
  }
  return block;
}

}  // namespace grip::solver::kernels
