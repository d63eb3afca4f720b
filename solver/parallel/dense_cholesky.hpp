#pragma once
// Small Newton systems of a batch solved directly, one environment per item: its whole matrix
// made dense from the 3x3 blocks of block_assembly.hpp, the fixed DOFs eliminated as the CPU
// engine eliminates them (NewtonSolver::eliminate_prescribed: their values kept, their share
// A_fc x_c taken from the free rows, their rows and columns the identity's), then factored by
// Cholesky and solved by the two triangular solves. For the systems of a rigid object and a
// hand's driven links (17 affine bodies: 204 DOFs, 20,910 entries in the lower triangle), which
// a direct solve finishes in n^3 / 3 flops where CG would take many iterations on their
// stiff drives; FEM systems (thousands of DOFs) go to CG (block_pcg.hpp). The factor is
// column-major in the lower triangle of each environment's n x n array. Each item reads and
// writes its own environment's values only: a solve is the same alone or in any batch.
#include <cmath>
#include <vector>

#include "solver/kernels/hd.hpp"

namespace grip::solver::parallel {

// What became of an environment's solve.
enum DenseStatus : int { kDenseSolved = 1, kDenseNotPositiveDefinite = 2 };

// L y = x, then L^T x = y, in x: the solve of L L^T x = x with the column-major lower triangle
// `a` that DenseCholeskyStage::factor leaves.
GRIP_HD inline void cholesky_substitute(int n, const double* a, double* x) {
  for (int i = 0; i < n; ++i) {
    double value = x[i];
    for (int k = 0; k < i; ++k) value -= a[i + n * k] * x[k];
    x[i] = value / a[i + n * i];
  }
  for (int i = n - 1; i >= 0; --i) {
    double value = x[i];
    for (int k = i + 1; k < n; ++k) value -= a[k + n * i] * x[k];
    x[i] = value / a[i + n * i];
  }
}

struct DenseCholeskyBuffers {
  int environment_count = 0;
  const int* dof_begin = nullptr;           // environments + 1 offsets into the batch's DOFs
  const int* block_begin = nullptr;         // environments + 1 offsets into the blocks
  const int* row = nullptr;                 // per block: its row unit in the batch (first DOF / 3)
  const int* column = nullptr;              // per block: its column unit (<= its row unit)
  const double* block = nullptr;            // 9 per block, column-major
  const char* fixed = nullptr;              // per DOF
  const double* rhs = nullptr;              // per DOF (read at free DOFs)
  const long long* matrix_begin = nullptr;  // environments + 1 offsets: n^2 per environment
  double* matrix = nullptr;                 // work: each environment's n x n array
  double* x = nullptr;    // per DOF: the fixed DOFs' values on entry, the solution after
  int* status = nullptr;  // per environment, a DenseStatus
};

struct DenseCholeskyStage {
  DenseCholeskyBuffers b;
  const unsigned char* solve = nullptr;  // per environment: 1 where it is solved; null: all

  GRIP_HD void operator()(int e) const {
    if (solve != nullptr && solve[e] == 0) return;
    const int first = b.dof_begin[e], n = b.dof_begin[e + 1] - first;
    double* a = b.matrix + b.matrix_begin[e];
    assemble(e, first, n, a);
    eliminate_fixed(first, n, a);
    if (!factor(n, a)) {
      b.status[e] = kDenseNotPositiveDefinite;
      return;
    }
    substitute(first, n, a);
    b.status[e] = kDenseSolved;
  }

  // The lower triangle of the environment's matrix from its blocks.
  GRIP_HD void assemble(int e, int first, int n, double* a) const {
    for (int j = 0; j < n; ++j) {
      for (int i = j; i < n; ++i) a[i + n * j] = 0.0;
    }
    for (int k = b.block_begin[e]; k < b.block_begin[e + 1]; ++k) {
      const int r0 = 3 * b.row[k] - first, c0 = 3 * b.column[k] - first;
      for (int j = 0; j < 3; ++j) {
        for (int i = 0; i < 3; ++i) {
          if (r0 + i >= c0 + j) a[(r0 + i) + n * (c0 + j)] += b.block[9 * k + 3 * j + i];
        }
      }
    }
  }

  // x's free rows: rhs less the fixed DOFs' share; then the fixed rows and columns the
  // identity's, so that the solve keeps their values.
  GRIP_HD void eliminate_fixed(int first, int n, double* a) const {
    for (int i = 0; i < n; ++i) {
      if (b.fixed[first + i] != 0) continue;
      double value = b.rhs[first + i];
      for (int j = 0; j < n; ++j) {
        if (b.fixed[first + j] == 0) continue;
        const double entry = i >= j ? a[i + n * j] : a[j + n * i];
        value -= entry * b.x[first + j];
      }
      b.x[first + i] = value;
    }
    for (int c = 0; c < n; ++c) {
      if (b.fixed[first + c] == 0) continue;
      for (int k = 0; k < c; ++k) a[c + n * k] = 0.0;
      for (int k = c + 1; k < n; ++k) a[k + n * c] = 0.0;
      a[c + n * c] = 1.0;
    }
  }

  // In place, column by column: L L^T = A; false at a pivot that is not positive.
  GRIP_HD static bool factor(int n, double* a) {
    for (int j = 0; j < n; ++j) {
      double pivot = a[j + n * j];
      for (int k = 0; k < j; ++k) pivot -= a[j + n * k] * a[j + n * k];
      if (!(pivot > 0.0)) return false;
      const double l = std::sqrt(pivot);
      a[j + n * j] = l;
      for (int i = j + 1; i < n; ++i) {
        double value = a[i + n * j];
        for (int k = 0; k < j; ++k) value -= a[i + n * k] * a[j + n * k];
        a[i + n * j] = value / l;
      }
    }
    return true;
  }

  GRIP_HD void substitute(int first, int n, const double* a) const {
    cholesky_substitute(n, a, b.x + first);
  }
};

// Each environment's offsets into the work array, for environments whose DOFs begin at
// `dof_begin`: n^2 entries for each that `solve` marks (null: all), none for the others.
inline std::vector<long long> dense_matrix_begin(const std::vector<int>& dof_begin,
                                                 const unsigned char* solve = nullptr) {
  std::vector<long long> begin{0};
  for (std::size_t e = 0; e + 1 < dof_begin.size(); ++e) {
    const long long n = dof_begin[e + 1] - dof_begin[e];
    begin.push_back(begin.back() + (solve == nullptr || solve[e] != 0 ? n * n : 0));
  }
  return begin;
}

}  // namespace grip::solver::parallel
