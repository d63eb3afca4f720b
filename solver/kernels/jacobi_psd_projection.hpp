#pragma once
// Projection of a small symmetric matrix onto the positive semi-definite cone, callable on a
// device: project_to_psd (psd_projection.hpp) relies on Eigen's SelfAdjointEigenSolver, which is
// host-only, so the data-parallel engine's stages use this one on every launcher. A Cholesky
// test first: a matrix it factors is returned bit for bit unchanged, as project_to_psd returns
// one; otherwise cyclic Jacobi rotations diagonalize it (accurate to a few ulps of its largest
// eigenvalue, even where eigenvalues repeat) and negative eigenvalues are clamped to zero.
#include <Eigen/Core>
#include <cmath>

#include "solver/kernels/hd.hpp"

namespace grip::solver::kernels {

// True when the symmetric matrix's Cholesky factorization succeeds (it is positive definite,
// to round-off), read from its lower triangle.
template <int N>
GRIP_HD inline bool cholesky_succeeds(const Eigen::Matrix<double, N, N>& h) {
  Eigen::Matrix<double, N, N> l = Eigen::Matrix<double, N, N>::Zero();
  for (int j = 0; j < N; ++j) {
    double d = h(j, j);
    for (int k = 0; k < j; ++k) d -= l(j, k) * l(j, k);
    if (!(d > 0.0)) return false;
    l(j, j) = std::sqrt(d);
    for (int i = j + 1; i < N; ++i) {
      double s = h(i, j);
      for (int k = 0; k < j; ++k) s -= l(i, k) * l(j, k);
      l(i, j) = s / l(j, j);
    }
  }
  return true;
}

// Eigen-decomposition of the symmetric matrix `a` by cyclic Jacobi sweeps: on return a is
// diagonal (its eigenvalues) to round-off and `v`'s columns are the eigenvectors.
template <int N>
GRIP_HD inline void jacobi_eigen_decomposition(Eigen::Matrix<double, N, N>& a,
                                               Eigen::Matrix<double, N, N>& v) {
  constexpr int kMaxSweeps = 50;  // quadratic convergence: 6 to 10 sweeps in practice
  v.setIdentity();
  for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
    double off = 0.0, diagonal = 0.0;
    for (int p = 0; p < N; ++p) {
      diagonal += a(p, p) * a(p, p);
      for (int q = p + 1; q < N; ++q) off += a(p, q) * a(p, q);
    }
    if (off <= 1e-32 * diagonal || off == 0.0) return;
    for (int p = 0; p < N - 1; ++p) {
      for (int q = p + 1; q < N; ++q) {
        if (a(p, q) == 0.0) continue;
        // The rotation that zeroes a(p, q) (Golub and Van Loan, Algorithm 8.5.1), its tangent
        // the smaller root.
        const double theta = (a(q, q) - a(p, p)) / (2.0 * a(p, q));
        const double t =
            (theta >= 0.0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
        const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
        for (int k = 0; k < N; ++k) {
          const double akp = a(k, p), akq = a(k, q);
          a(k, p) = c * akp - s * akq;
          a(k, q) = s * akp + c * akq;
        }
        for (int k = 0; k < N; ++k) {
          const double apk = a(p, k), aqk = a(q, k);
          a(p, k) = c * apk - s * aqk;
          a(q, k) = s * apk + c * aqk;
        }
        for (int k = 0; k < N; ++k) {
          const double vkp = v(k, p), vkq = v(k, q);
          v(k, p) = c * vkp - s * vkq;
          v(k, q) = s * vkp + c * vkq;
        }
      }
    }
  }
}

// The nearest positive semi-definite matrix to the symmetric h (Frobenius norm).
template <int N>
GRIP_HD inline Eigen::Matrix<double, N, N> project_to_psd_jacobi(
    const Eigen::Matrix<double, N, N>& h) {
  if (cholesky_succeeds<N>(h)) return h;
  Eigen::Matrix<double, N, N> a = h, v;
  jacobi_eigen_decomposition<N>(a, v);
  bool negative = false;
  for (int k = 0; k < N; ++k) negative = negative || a(k, k) < 0.0;
  if (!negative) return h;
  Eigen::Matrix<double, N, N> projected = Eigen::Matrix<double, N, N>::Zero();
  for (int k = 0; k < N; ++k) {
    if (a(k, k) > 0.0) projected += a(k, k) * v.col(k) * v.col(k).transpose();
  }
  return projected;
}

}  // namespace grip::solver::kernels
