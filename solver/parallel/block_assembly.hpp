#pragma once
// A batch's Newton matrices as 3x3 blocks. A DOF "unit" is three consecutive DOFs of the batch:
// an FEM vertex is one unit, an affine body four (p and the rows a1, a2, a3 of A). Each
// environment's matrix is the lower triangle (row unit >= column unit; a diagonal block whole) of
// the sum over its stencils of J^T H J. A stencil is four slots and a 12x12 Hessian in their
// positions: a contact pair's (barrier, friction) at its collision vertices, a tet's at its
// vertices, or an affine body's own (inertia, orthogonality, drive) at its four units. J maps a
// slot's DOF block to its position: the identity for an FEM vertex or a unit; for an affine
// body's vertex at rest point xbar, I for p and e_i xbar^T for a_i (x_i = p_i + a_i . xbar).
// The FEM vertices' lumped masses go onto their diagonal blocks afterwards (MassDiagonalStage).
//
// The pattern (which blocks, and which (slot, slot, unit, unit) terms sum into each, in a fixed
// order) is built on the host whenever the contact pairs change (a device would sort the terms
// by block); BlockAssemblyStage then sums each block's terms, one item per block, no atomics:
// the same sums on every launcher.
#include <vector>

#include "solver/kernels/hd.hpp"
#include "solver/parallel/affine_batch.hpp"
#include "solver/parallel/collision_batch.hpp"
#include "solver/parallel/fem_batch.hpp"

namespace grip::solver::parallel {

// The stencils' slots, 4 per stencil, in stencil order: per slot the first DOF and size of the
// DOF block it moves with (-1 and 0: none, a scripted vertex) and its rest point (an affine
// body's vertex; zeros otherwise).
struct StencilSlots {
  std::vector<int> dof, size;
  std::vector<double> rest;
  int stencil_count() const { return static_cast<int>(dof.size() / 4); }
  void add(int block_dof, int block_size, double x, double y, double z);
};

// Each tet of `fem` as a stencil of its four vertices.
void add_tet_stencils(const FemBatch& fem, StencilSlots& slots);
// Each affine body of `affine` as a stencil of its four units.
void add_affine_stencils(const AffineBatch& affine, StencilSlots& slots);
// Each pair (4 collision vertices of `collision` each) as a stencil.
void add_contact_stencils(const CollisionBatch& collision, const int* pair_vertex, int pair_count,
                          StencilSlots& slots);

// What the stage reads of the pattern: raw pointers into host or device memory.
struct BlockPatternBuffers {
  int count = 0;                    // blocks
  const int* row = nullptr;         // per block: its row unit in the batch (its first DOF / 3)
  const int* column = nullptr;      // per block: its column unit
  const int* begin = nullptr;       // count + 1 offsets into the terms
  const int* term_slots = nullptr;  // 2 per term: slots 4 s + a and 4 s + b of stencil s
  const int* term_units = nullptr;  // 2 per term: the units of a's and b's DOF blocks (0 to 3)
};

struct BlockPattern {
  std::vector<int> row, column, begin, term_slots, term_units;
  std::vector<int> environment_begin;  // environment_count + 1 offsets into the blocks
  BlockPatternBuffers buffers() const;
  // The block (u, u) of each unit u in `units` (-1: none).
  std::vector<int> diagonal_blocks(const std::vector<int>& units) const;
};

// The blocks the stencils touch, sorted by (row, column), each block's terms in (stencil, a, b,
// unit of a, unit of b) order; `dof_begin` splits them by environment.
BlockPattern block_pattern(const StencilSlots& slots, const std::vector<int>& dof_begin);

// J of a slot for one unit of its DOF block, as a 3x3 matrix (column-major): the identity, or
// e_i xbar^T for unit i = 1..3 of an affine body's vertex.
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
  const double* slot_rest = nullptr;        // 3 per slot (StencilSlots::rest)
  const double* stencil_hessian = nullptr;  // 144 per stencil, column-major
  double* block = nullptr;                  // 9 per block, column-major

  GRIP_HD void operator()(int b) const {
    double sum[9] = {};
    for (int t = pattern.begin[b]; t < pattern.begin[b + 1]; ++t) {
      const int slot_a = pattern.term_slots[2 * t], slot_b = pattern.term_slots[2 * t + 1];
      const int s = slot_a / 4, corner_a = slot_a % 4, corner_b = slot_b % 4;
      double ja[9], jb[9], h[9], hj[9];
      unit_jacobian(pattern.term_units[2 * t], slot_rest + 3 * slot_a, ja);
      unit_jacobian(pattern.term_units[2 * t + 1], slot_rest + 3 * slot_b, jb);
      const double* stencil = stencil_hessian + 144 * s;
      for (int col = 0; col < 3; ++col) {
        for (int row = 0; row < 3; ++row) {
          h[3 * col + row] = stencil[12 * (3 * corner_b + col) + 3 * corner_a + row];
        }
      }
      for (int col = 0; col < 3; ++col) {  // hj = H_ab J_b
        for (int row = 0; row < 3; ++row) {
          double x = 0.0;
          for (int m = 0; m < 3; ++m) x += h[3 * m + row] * jb[3 * col + m];
          hj[3 * col + row] = x;
        }
      }
      for (int col = 0; col < 3; ++col) {  // sum += J_a^T hj
        for (int row = 0; row < 3; ++row) {
          double x = 0.0;
          for (int m = 0; m < 3; ++m) x += ja[3 * row + m] * hj[3 * col + m];
          sum[3 * col + row] += x;
        }
      }
    }
    for (int k = 0; k < 9; ++k) block[9 * b + k] = sum[k];
  }
};

// An affine body's own 12x12 Hessian in its DOFs: M (inertia) + (k / m) M (a drive) + the
// orthogonality block on the rows of A (OrthogonalityStage's, projected); with `h`, the
// incremental potential's M + h^2 ((k / m) M + orthogonality).
struct AffineHessianStage {
  AffineBuffers bodies;
  const double* orthogonality = nullptr;  // 81 per body
  double* hessian = nullptr;              // 144 per body, column-major
  const double* h = nullptr;              // per environment; null: the terms unscaled

  GRIP_HD void operator()(int i) const {
    const double* m = bodies.mass_matrix + 144 * i;
    const double step = h == nullptr ? 1.0 : h[bodies.environment[i]], h2 = step * step;
    const double scale = 1.0 + h2 * (bodies.drive_stiffness[i] / m[0]);
    double* out = hessian + 144 * i;
    for (int k = 0; k < 144; ++k) out[k] = scale * m[k];
    for (int c = 0; c < 9; ++c) {
      for (int r = 0; r < 9; ++r) {
        out[12 * (3 + c) + 3 + r] += h2 * orthogonality[81 * i + 9 * c + r];
      }
    }
  }
};

// Each FEM vertex's lumped mass onto its diagonal block: m I.
struct MassDiagonalStage {
  VertexBuffers vertices;
  const int* diagonal = nullptr;  // per vertex: its diagonal block (BlockPattern::diagonal_blocks)
  double* block = nullptr;        // 9 per block

  GRIP_HD void operator()(int v) const {
    double* b = block + 9 * diagonal[v];
    for (int k = 0; k < 3; ++k) b[4 * k] += vertices.mass[v];
  }
};

}  // namespace grip::solver::parallel
