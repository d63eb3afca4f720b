#pragma once
// The coarse level of the data-parallel engine's two-level additive Schwarz preconditioner
// (block_pcg.hpp): M^-1 = D^-1 + P A_c^-1 P^T, D the block-Jacobi blocks, P the translations of
// aggregates of an environment's FEM vertices (each aggregate's free DOFs moving together, 3 per
// aggregate), A_c = P^T A P. Block-Jacobi alone leaves the smooth, long-wavelength errors of a
// long soft finger to hundreds of CG iterations; the coarse level solves for them directly.
// Aggregates are grown breadth-first through shared tets, so each is a compact patch of one
// body's mesh. A_c is dense per environment (3 rows per aggregate), assembled from the Newton
// matrix's blocks in a fixed order and factored by Cholesky once per linear solve; each CG
// iteration restricts the residual, solves, and adds the correction. Affine bodies have no
// aggregate (their 12x12 Jacobi blocks already hold them whole). Each item reads and writes its
// own environment's values only, so a solve is the same alone or in any batch.
#include <vector>

#include "solver/kernels/hd.hpp"
#include "solver/parallel/dense_cholesky.hpp"
#include "solver/parallel/fem_batch.hpp"

namespace grip::solver::parallel {

// FEM vertices per aggregate. Smaller aggregates cut more CG iterations but make A_c larger
// (its factor costs (3 C)^3 / 3 per solve): on a production fin-ray trial, 0 (block Jacobi
// alone) / 8 / 16 / 32 / 64 took 60,915 / 14,077 / 16,787 / 18,217 / 23,788 CG iterations and
// 30 / 58 / 29 / 23 / 30 s on the host launcher (docs/simulation.md).
constexpr int kCoarseAggregateVertices = 32;

// What the stages read and write: raw pointers into host or device memory.
struct CoarseBuffers {
  int aggregate_count = 0;                    // 0: no coarse level
  const int* unit_aggregate = nullptr;        // per unit: its aggregate, -1 none
  const int* aggregate_unit_begin = nullptr;  // aggregates + 1 offsets into aggregate_unit
  const int* aggregate_unit = nullptr;        // each aggregate's units, ascending
  const int* aggregate_begin = nullptr;       // environments + 1 offsets into the aggregates
  const int* block_begin = nullptr;           // environments + 1 offsets into the matrix's blocks
  const long long* matrix_begin = nullptr;    // environments + 1 offsets: (3 C)^2 each
  double* matrix = nullptr;  // work: each environment's A_c (lower triangle), then its factor
  double* vector = nullptr;  // work: 3 per aggregate: P^T r, then A_c^-1 P^T r
  char* ok = nullptr;        // per environment: A_c was positive definite
};

// The coarse level's structure, built on the host.
struct CoarseSpace {
  std::vector<int> unit_aggregate, aggregate_unit_begin{0}, aggregate_unit, aggregate_begin;
  std::vector<long long> matrix_begin;
  int aggregate_count() const { return static_cast<int>(aggregate_unit_begin.size()) - 1; }
};

// The aggregates of `fem`'s vertices, up to `vertices` each (0: no coarse level), for a batch
// of `unit_count` units whose environments begin at the units `unit_begin`.
CoarseSpace coarse_space(const FemBatch& fem, int vertices, int unit_count,
                         const std::vector<int>& unit_begin);

// Where the coarse matrix's entry (r, c) lies in an n x n column-major lower triangle.
GRIP_HD inline long long coarse_lower(int r, int c, int n) {
  return r >= c ? r + static_cast<long long>(n) * c : c + static_cast<long long>(n) * r;
}

}  // namespace grip::solver::parallel
