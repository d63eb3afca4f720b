#pragma once
// The contact pairs' Hessians of a batch in its Newton matrices, as 3x3 blocks. A DOF "unit" is
// three consecutive DOFs of the batch: an FEM vertex is one unit, an affine body four (p and the
// rows a1, a2, a3 of A). Each environment's matrix is the lower triangle (row unit >= column
// unit; a diagonal block whole) of sum over pairs of J^T H J, H a pair's 12x12 position-space
// Hessian (barrier or friction stage) and J the map from its vertices' DOFs to their positions:
// the identity for an FEM vertex; for an affine body's vertex at rest point xbar, I for p and
// e_i xbar^T for a_i (x_i = p_i + a_i . xbar).
//
// The pattern (which blocks, and which (pair, corner, corner, unit, unit) terms sum into each, in
// a fixed order) is built on the host from the pairs whenever they change (a device would sort
// the terms by block); BlockAssemblyStage then sums each block's terms, one item per block, no
// atomics: the same sums on every launcher.
#include <vector>

#include "solver/kernels/hd.hpp"
#include "solver/parallel/collision_batch.hpp"

namespace grip::solver::parallel {

// What the stage reads of the pattern: raw pointers into host or device memory.
struct BlockPatternBuffers {
  int count = 0;                    // blocks
  const int* row = nullptr;         // per block: its row unit in the batch (its first DOF / 3)
  const int* column = nullptr;      // per block: its column unit
  const int* begin = nullptr;       // count + 1 offsets into the terms
  const int* term_slots = nullptr;  // 2 per term: the slots 4 k + a and 4 k + b of pair k
  const int* term_units = nullptr;  // 2 per term: the units of a's and b's DOF blocks (0 to 3)
};

struct BlockPattern {
  std::vector<int> row, column, begin, term_slots, term_units;
  std::vector<int> environment_begin;  // environment_count + 1 offsets into the blocks
  BlockPatternBuffers buffers() const;
};

// The blocks `pair_count` pairs (`pair_vertex`, 4 each, the batch's numbering) touch, sorted by
// (row, column), each block's terms in (pair, a, b, unit of a, unit of b) order.
BlockPattern contact_block_pattern(const CollisionBatch& batch, const int* pair_vertex,
                                   int pair_count);

// J of a collision vertex for one unit of its DOF block, as a 3x3 matrix (column-major):
// the identity, or e_i xbar^T for unit i = 1..3 of an affine body.
GRIP_HD inline void unit_jacobian(int unit, const double* xbar, double* j) {
  for (int k = 0; k < 9; ++k) j[k] = 0.0;
  if (unit == 0) {
    j[0] = j[4] = j[8] = 1.0;
    return;
  }
  for (int c = 0; c < 3; ++c) j[3 * c + (unit - 1)] = xbar[c];  // row unit - 1 holds xbar^T
}

struct BlockAssemblyStage {
  BlockPatternBuffers pattern;
  const int* pair_vertex = nullptr;      // 4 per pair
  const double* rest = nullptr;          // 3 per collision vertex (affine rest points)
  const double* pair_hessian = nullptr;  // 144 per pair, column-major, position space
  double* block = nullptr;               // 9 per block, column-major

  GRIP_HD void operator()(int b) const {
    double sum[9] = {};
    for (int t = pattern.begin[b]; t < pattern.begin[b + 1]; ++t) {
      const int slot_a = pattern.term_slots[2 * t], slot_b = pattern.term_slots[2 * t + 1];
      const int k = slot_a / 4, corner_a = slot_a % 4, corner_b = slot_b % 4;
      double ja[9], jb[9], h[9], hj[9];
      unit_jacobian(pattern.term_units[2 * t], rest + 3 * pair_vertex[slot_a], ja);
      unit_jacobian(pattern.term_units[2 * t + 1], rest + 3 * pair_vertex[slot_b], jb);
      const double* pair = pair_hessian + 144 * k;
      for (int col = 0; col < 3; ++col) {
        for (int row = 0; row < 3; ++row) {
          h[3 * col + row] = pair[12 * (3 * corner_b + col) + 3 * corner_a + row];
        }
      }
      for (int col = 0; col < 3; ++col) {  // hj = H_ab J_b
        for (int row = 0; row < 3; ++row) {
          double s = 0.0;
          for (int m = 0; m < 3; ++m) s += h[3 * m + row] * jb[3 * col + m];
          hj[3 * col + row] = s;
        }
      }
      for (int col = 0; col < 3; ++col) {  // sum += J_a^T hj
        for (int row = 0; row < 3; ++row) {
          double s = 0.0;
          for (int m = 0; m < 3; ++m) s += ja[3 * row + m] * hj[3 * col + m];
          sum[3 * col + row] += s;
        }
      }
    }
    for (int k = 0; k < 9; ++k) block[9 * b + k] = sum[k];
  }
};

}  // namespace grip::solver::parallel
