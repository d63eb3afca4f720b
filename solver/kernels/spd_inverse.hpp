#pragma once
// The inverse of a small symmetric positive-definite matrix by Cholesky, callable on a device:
// the data-parallel engine's block-Jacobi preconditioner inverts each DOF block's diagonal
// block of the Newton matrix with it (3x3 for an FEM vertex, 12x12 for an affine body) once per
// linear solve, then applies the inverse as one small product per CG iteration.
#include <cmath>

#include "solver/kernels/hd.hpp"

namespace grip::solver::kernels {

constexpr int kMaxSpdInverseSize = 12;

// Writes the inverse of the n x n symmetric matrix `a` (column-major, lower triangle read; n at
// most kMaxSpdInverseSize) into `inverse` (column-major, whole). False, `inverse` unspecified,
// when a pivot is not positive: the matrix is not positive definite to round-off.
GRIP_HD inline bool spd_inverse(const double* a, int n, double* inverse) {
  double l[kMaxSpdInverseSize * kMaxSpdInverseSize];  // the Cholesky factor, column-major
  for (int j = 0; j < n; ++j) {
    double d = a[n * j + j];
    for (int k = 0; k < j; ++k) d -= l[n * k + j] * l[n * k + j];
    if (!(d > 0.0)) return false;
    l[n * j + j] = std::sqrt(d);
    for (int i = j + 1; i < n; ++i) {
      double s = a[n * j + i];
      for (int k = 0; k < j; ++k) s -= l[n * k + i] * l[n * k + j];
      l[n * j + i] = s / l[n * j + j];
    }
  }
  // Column c of the inverse solves L L^T x = e_c: forward, then backward substitution.
  for (int c = 0; c < n; ++c) {
    double* x = inverse + n * c;
    for (int i = 0; i < n; ++i) {
      double s = i == c ? 1.0 : 0.0;
      for (int k = 0; k < i; ++k) s -= l[n * k + i] * x[k];
      x[i] = s / l[n * i + i];
    }
    for (int i = n - 1; i >= 0; --i) {
      double s = x[i];
      for (int k = i + 1; k < n; ++k) s -= l[n * i + k] * x[k];
      x[i] = s / l[n * i + i];
    }
  }
  return true;
}

}  // namespace grip::solver::kernels
