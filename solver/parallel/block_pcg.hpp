#pragma once
// Every environment's Newton system of a batch solved at once by preconditioned conjugate
// gradients on the 3x3 blocks of block_assembly.hpp, each environment with its own scalars
// (step lengths, residuals, tolerance, iteration count, status). The preconditioner is two-level
// additive Schwarz: block Jacobi over DOF blocks (an FEM vertex's 3x3 diagonal block, an affine
// body's whole 12x12: its position and matrix rows are coupled strongly, and on different
// scales) plus, where a batch has FEM bodies, a coarse level over aggregates of their vertices
// (coarse_space.hpp).
//
// Fixed DOFs (pinned, held) keep the values x holds on entry: the solve is the CPU engine's
// elimination (NewtonSolver::eliminate_prescribed), A_ff x_f = b_f - A_fc x_c, done as CG on
// the free DOFs with the fixed ones' contribution in the first residual.
//
// Isolation: every stage of an environment reads only that environment's values, and an
// environment that has converged, hit the iteration limit or broken down is frozen (its
// vectors and scalars no longer change) while others go on, so an environment's solution and
// iteration count are the same, bit for bit, alone or in any batch. Reductions are sums over
// each environment's units in unit order: the same on every launcher, no atomics. The host
// reads one number per iteration: how many environments still run.
#include <cmath>
#include <vector>

#include "solver/kernels/hd.hpp"
#include "solver/kernels/spd_inverse.hpp"
#include "solver/parallel/affine_batch.hpp"
#include "solver/parallel/block_assembly.hpp"
#include "solver/parallel/coarse_space.hpp"
#include "solver/parallel/fem_batch.hpp"
#include "solver/parallel/launch.hpp"

namespace grip::solver::parallel {

// What became of an environment's solve.
enum PcgStatus : int {
  kPcgRunning = 0,
  kPcgConverged = 1,         // |r| <= tolerance |r0|
  kPcgIterationLimit = 2,    // not converged within the iteration limit
  kPcgIndefinite = 3,        // a direction of non-positive curvature: the matrix is not SPD
  kPcgBadPreconditioner = 4  // a DOF block's diagonal block, or the coarse matrix, is not
                             // positive definite
};

// Per unit, the blocks of its row of the whole symmetric matrix: each lower block (u, c) as it
// is and each lower block (r, u), r > u, transposed, in block order.
struct BlockRowBuffers {
  const int* begin = nullptr;  // units + 1 offsets
  const int* entry = nullptr;  // 2 b for block b, 2 b + 1 for its transpose
};

struct BlockRows {
  std::vector<int> begin, entry;
};

BlockRows block_rows(const BlockPattern& pattern, int unit_count);

// The preconditioner's DOF blocks, in unit order: per block its first unit, its unit count (1
// or 4) and the pattern's blocks within it, 10 per DOF block: (i, j), i >= j, in the order
// (0,0) (1,0) (1,1) (2,0) (2,1) (2,2) (3,0) ... (3,3); -1 past its units.
struct JacobiBuffers {
  int count = 0;
  const int* first_unit = nullptr;
  const int* units = nullptr;
  const int* matrix_block = nullptr;
};

struct JacobiBlocks {
  std::vector<int> first_unit, units, matrix_block;
  std::vector<int> environment_begin;  // environment_count + 1 offsets into the DOF blocks
};

// The FEM vertices of `fem` and the affine bodies of `affine` as DOF blocks of `pattern`
// (which must hold every DOF block's diagonal blocks); `dof_begin` splits them by environment.
JacobiBlocks jacobi_blocks(const FemBatch& fem, const AffineBatch& affine,
                           const BlockPattern& pattern, const std::vector<int>& dof_begin);

// Everything the stages read and write: raw pointers into host or device memory.
struct PcgBuffers {
  // The matrices and their structure.
  BlockPatternBuffers pattern;
  const double* block = nullptr;  // 9 per block, column-major
  BlockRowBuffers rows;
  JacobiBuffers jacobi;
  CoarseBuffers coarse;
  int unit_count = 0;
  const int* unit_environment = nullptr;  // per unit
  const char* fixed = nullptr;            // per DOF
  // Per environment: its units and DOF blocks (environments + 1 offsets each), its relative
  // tolerance, and what the solve found.
  int environment_count = 0;
  const int* unit_begin = nullptr;
  const int* jacobi_begin = nullptr;
  const double* tolerance = nullptr;
  int max_iterations = 0;
  int* status = nullptr;       // PcgStatus
  int* iterations = nullptr;   // CG iterations taken
  double* residual = nullptr;  // |r| / |r0| at the end (0 when r0 = 0)
  // The right-hand side, the solution (fixed DOFs' values on entry, free ones' first guess).
  const double* rhs = nullptr;
  double* x = nullptr;
  // Work: per DOF r, z, d, q; per unit a partial dot product; per DOF block its inverse (144);
  // per environment rz, rz of the next iterate, rr, rr0, pAp, alpha, beta; a running count.
  double *r = nullptr, *z = nullptr, *d = nullptr, *q = nullptr, *partial = nullptr;
  double* jacobi_inverse = nullptr;
  char* jacobi_ok = nullptr;
  double *rz = nullptr, *rz_next = nullptr, *rr = nullptr, *rr0 = nullptr, *pap = nullptr;
  double *alpha = nullptr, *beta = nullptr;
  int* running = nullptr;  // one int
  // Per environment: 1 where another solver takes the system (dense_cholesky.hpp): it is left
  // converged at once, its x untouched; null: none.
  const unsigned char* skip = nullptr;
};

GRIP_HD inline bool pcg_running(const PcgBuffers& p, int unit) {
  return p.status[p.unit_environment[unit]] == kPcgRunning;
}

// y = A v on the free rows (0 on fixed ones), one item per unit.
struct BlockProductStage {
  PcgBuffers p;
  const double* v = nullptr;
  double* y = nullptr;

  GRIP_HD void operator()(int u) const {
    double sum[3] = {};
    for (int k = p.rows.begin[u]; k < p.rows.begin[u + 1]; ++k) {
      const int b = p.rows.entry[k] / 2;
      const bool transposed = p.rows.entry[k] % 2 == 1;
      const double* m = p.block + 9 * b;
      const double* w = v + 3 * (transposed ? p.pattern.row[b] : p.pattern.column[b]);
      for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) sum[r] += (transposed ? m[3 * r + c] : m[3 * c + r]) * w[c];
      }
    }
    for (int r = 0; r < 3; ++r) y[3 * u + r] = p.fixed[3 * u + r] ? 0.0 : sum[r];
  }
};

// r = b - A x on the free DOFs (A x in q), 0 on fixed ones.
struct FirstResidualStage {
  PcgBuffers p;
  GRIP_HD void operator()(int i) const { p.r[i] = p.fixed[i] ? 0.0 : p.rhs[i] - p.q[i]; }
};

// Each DOF block's inverse diagonal block, fixed DOFs' rows and columns set to the identity's.
struct JacobiFactorStage {
  PcgBuffers p;

  GRIP_HD void operator()(int j) const {
    const int n = 3 * p.jacobi.units[j], first = 3 * p.jacobi.first_unit[j];
    double a[kernels::kMaxSpdInverseSize * kernels::kMaxSpdInverseSize];
    int k = 0;
    for (int bi = 0; bi < p.jacobi.units[j]; ++bi) {
      for (int bj = 0; bj <= bi; ++bj, ++k) {
        const double* m = p.block + 9 * p.jacobi.matrix_block[10 * j + k];
        for (int c = 0; c < 3; ++c) {
          for (int r = 0; r < 3; ++r) a[n * (3 * bj + c) + 3 * bi + r] = m[3 * c + r];
        }
      }
    }
    for (int i = 0; i < n; ++i) {
      if (!p.fixed[first + i]) continue;
      for (int c = 0; c < n; ++c) a[n * c + i] = a[n * i + c] = 0.0;
      a[n * i + i] = 1.0;
    }
    p.jacobi_ok[j] = kernels::spd_inverse(a, n, p.jacobi_inverse + 144 * j) ? 1 : 0;
  }
};

// z = M^-1 r on a DOF block of a running environment.
struct PreconditionStage {
  PcgBuffers p;

  GRIP_HD void operator()(int j) const {
    const int n = 3 * p.jacobi.units[j], first = 3 * p.jacobi.first_unit[j];
    if (!pcg_running(p, p.jacobi.first_unit[j])) return;
    const double* inverse = p.jacobi_inverse + 144 * j;
    for (int r = 0; r < n; ++r) {
      double s = 0.0;
      for (int c = 0; c < n; ++c) s += inverse[n * c + r] * p.r[first + c];
      p.z[first + r] = s;
    }
  }
};

// Each running environment's coarse matrix P^T A P over its free DOFs (an aggregate's rows
// with no free DOF the identity's), factored in place. A block (u, w) of A, u > w, stands for
// itself and its transpose (w, u): it adds to (r, c) and (c, r) of A_c, one entry of the lower
// triangle, or twice to a diagonal entry where the two coincide.
struct CoarseFactorStage {
  PcgBuffers p;

  GRIP_HD void operator()(int e) const {
    const CoarseBuffers& c = p.coarse;
    const int first = c.aggregate_begin[e], n = 3 * (c.aggregate_begin[e + 1] - first);
    c.ok[e] = 1;
    if (n == 0 || p.status[e] != kPcgRunning) return;
    double* a = c.matrix + c.matrix_begin[e];
    for (long long k = 0; k < static_cast<long long>(n) * n; ++k) a[k] = 0.0;
    for (int k = c.block_begin[e]; k < c.block_begin[e + 1]; ++k) add_block(k, first, n, a);
    for (int i = 0; i < n; ++i) {
      if (a[coarse_lower(i, i, n)] == 0.0) a[coarse_lower(i, i, n)] = 1.0;
    }
    c.ok[e] = DenseCholeskyStage::factor(n, a) ? 1 : 0;
  }

  GRIP_HD void add_block(int k, int first, int n, double* a) const {
    const int u = p.pattern.row[k], w = p.pattern.column[k];
    const int au = p.coarse.unit_aggregate[u], aw = p.coarse.unit_aggregate[w];
    if (au < 0 || aw < 0) return;
    for (int j = 0; j < 3; ++j) {
      for (int i = 0; i < 3; ++i) {
        if (p.fixed[3 * u + i] || p.fixed[3 * w + j]) continue;
        if (u == w && i < j) continue;  // a diagonal block's upper half is its lower's
        const int r = 3 * (au - first) + i, col = 3 * (aw - first) + j;
        const double value = p.block[9 * k + 3 * j + i];
        a[coarse_lower(r, col, n)] += u != w && r == col ? 2.0 * value : value;
      }
    }
  }
};

// P^T r: each aggregate's sum of its free residuals, per axis.
struct CoarseRestrictStage {
  PcgBuffers p;

  GRIP_HD void operator()(int g) const {
    const CoarseBuffers& c = p.coarse;
    const int begin = c.aggregate_unit_begin[g], end = c.aggregate_unit_begin[g + 1];
    if (!pcg_running(p, c.aggregate_unit[begin])) return;
    double sum[3] = {};
    for (int k = begin; k < end; ++k) {
      const int u = c.aggregate_unit[k];
      for (int i = 0; i < 3; ++i) sum[i] += p.fixed[3 * u + i] ? 0.0 : p.r[3 * u + i];
    }
    for (int i = 0; i < 3; ++i) c.vector[3 * g + i] = sum[i];
  }
};

// A_c^-1 P^T r by the factor, per running environment.
struct CoarseSolveStage {
  PcgBuffers p;

  GRIP_HD void operator()(int e) const {
    const CoarseBuffers& c = p.coarse;
    const int first = c.aggregate_begin[e], n = 3 * (c.aggregate_begin[e + 1] - first);
    if (n == 0 || p.status[e] != kPcgRunning) return;
    cholesky_substitute(n, c.matrix + c.matrix_begin[e], c.vector + 3 * first);
  }
};

// z += P A_c^-1 P^T r on each free DOF of an aggregate's unit.
struct CoarseProlongStage {
  PcgBuffers p;

  GRIP_HD void operator()(int u) const {
    const int g = p.coarse.unit_aggregate[u];
    if (g < 0 || !pcg_running(p, u)) return;
    for (int i = 0; i < 3; ++i) {
      if (!p.fixed[3 * u + i]) p.z[3 * u + i] += p.coarse.vector[3 * g + i];
    }
  }
};

// partial[u] = a . b over unit u's three DOFs.
struct UnitDotStage {
  const double* a = nullptr;
  const double* b = nullptr;
  double* partial = nullptr;

  GRIP_HD void operator()(int u) const {
    partial[u] = a[3 * u] * b[3 * u] + a[3 * u + 1] * b[3 * u + 1] + a[3 * u + 2] * b[3 * u + 2];
  }
};

// out[e] = the sum of environment e's partial dot products, in unit order; running ones only.
struct EnvironmentDotStage {
  PcgBuffers p;
  double* out = nullptr;

  GRIP_HD void operator()(int e) const {
    if (p.status[e] != kPcgRunning) return;
    double sum = 0.0;
    for (int u = p.unit_begin[e]; u < p.unit_begin[e + 1]; ++u) sum += p.partial[u];
    out[e] = sum;
  }
};

struct PcgResetStage {
  PcgBuffers p;
  GRIP_HD void operator()(int e) const {
    p.status[e] = p.skip != nullptr && p.skip[e] != 0 ? kPcgConverged : kPcgRunning;
  }
};

// After the first residual and its preconditioned copy: each environment's r0, and whether it
// has anything to solve.
struct PcgStartStage {
  PcgBuffers p;

  GRIP_HD void operator()(int e) const {
    p.iterations[e] = 0;
    p.residual[e] = 0.0;
    p.rr0[e] = p.rr[e];
    if (p.status[e] != kPcgRunning) return;  // skipped
    for (int j = p.jacobi_begin[e]; j < p.jacobi_begin[e + 1]; ++j) {
      if (!p.jacobi_ok[j]) {
        p.status[e] = kPcgBadPreconditioner;
        return;
      }
    }
    if (p.coarse.aggregate_count > 0 && !p.coarse.ok[e]) {
      p.status[e] = kPcgBadPreconditioner;
      return;
    }
    if (p.rr[e] == 0.0) {
      p.status[e] = kPcgConverged;
    } else if (!(p.rz[e] > 0.0)) {
      p.status[e] = kPcgIndefinite;
    }
  }
};

// alpha = rz / pAp; a direction of non-positive curvature stops the environment.
struct StepLengthStage {
  PcgBuffers p;

  GRIP_HD void operator()(int e) const {
    if (p.status[e] != kPcgRunning) return;
    if (!(p.pap[e] > 0.0)) {
      p.status[e] = kPcgIndefinite;
      return;
    }
    p.alpha[e] = p.rz[e] / p.pap[e];
  }
};

// x += alpha d, r -= alpha q on a running environment's DOFs.
struct StepStage {
  PcgBuffers p;

  GRIP_HD void operator()(int i) const {
    if (!pcg_running(p, i / 3)) return;
    const double alpha = p.alpha[p.unit_environment[i / 3]];
    p.x[i] += alpha * p.d[i];
    p.r[i] -= alpha * p.q[i];
  }
};

// After a step: the iteration counted, convergence tested, beta for the next direction.
struct NextDirectionStage {
  PcgBuffers p;

  GRIP_HD void operator()(int e) const {
    if (p.status[e] != kPcgRunning) return;
    const int taken = ++p.iterations[e];
    const double tolerance = p.tolerance[e];
    p.residual[e] = std::sqrt(p.rr[e] / p.rr0[e]);
    if (p.rr[e] <= tolerance * tolerance * p.rr0[e]) {
      p.status[e] = kPcgConverged;
    } else if (taken >= p.max_iterations) {
      p.status[e] = kPcgIterationLimit;
    } else if (!(p.rz_next[e] > 0.0)) {
      p.status[e] = kPcgIndefinite;
    } else {
      p.beta[e] = p.rz_next[e] / p.rz[e];
      p.rz[e] = p.rz_next[e];
    }
  }
};

// d = z + beta d on a running environment's DOFs (d = z first).
struct DirectionStage {
  PcgBuffers p;
  bool first = false;

  GRIP_HD void operator()(int i) const {
    if (!pcg_running(p, i / 3)) return;
    p.d[i] = first ? p.z[i] : p.z[i] + p.beta[p.unit_environment[i / 3]] * p.d[i];
  }
};

// The rz and rr of every running environment's current r (z = M^-1 r computed here).
template <class Launcher>
void launch_preconditioned_dots(Launcher& launch, const PcgBuffers& p, double* rz) {
  launch(p.jacobi.count, PreconditionStage{p});
  if (p.coarse.aggregate_count > 0) {
    launch(p.coarse.aggregate_count, CoarseRestrictStage{p});
    launch(p.environment_count, CoarseSolveStage{p});
    launch(p.unit_count, CoarseProlongStage{p});
  }
  launch(p.unit_count, UnitDotStage{p.r, p.z, p.partial});
  launch(p.environment_count, EnvironmentDotStage{p, rz});
  launch(p.unit_count, UnitDotStage{p.r, p.r, p.partial});
  launch(p.environment_count, EnvironmentDotStage{p, p.rr});
}

// How many CG iterations a launcher runs between reads of the running count: its
// poll_interval where it has one, else 1. On a GPU a read stalls the host until the device has
// drained, so that each iteration's launches wait for the last; iterations after every
// environment has stopped change nothing (each stage leaves a stopped environment as it is), so
// the solutions, iterations and statuses do not depend on it.
template <class Launcher>
int poll_interval(const Launcher& launch) {
  if constexpr (requires { launch.poll_interval; }) {
    return launch.poll_interval;
  } else {
    return 1;
  }
}

// Solves every environment's system; afterwards status, iterations and residual say how each
// went. The launcher's fetch() reads the running count; every other value stays where it is.
template <class Launcher>
void solve_block_pcg(Launcher& launch, const PcgBuffers& p) {
  const int dofs = 3 * p.unit_count;
  launch(p.environment_count, PcgResetStage{p});
  launch(p.jacobi.count, JacobiFactorStage{p});
  if (p.coarse.aggregate_count > 0) launch(p.environment_count, CoarseFactorStage{p});
  launch(p.unit_count, BlockProductStage{p, p.x, p.q});
  launch(dofs, FirstResidualStage{p});
  launch_preconditioned_dots(launch, p, p.rz);
  launch(p.environment_count, PcgStartStage{p});
  launch(dofs, DirectionStage{p, true});
  const int poll = poll_interval(launch);
  for (int iteration = 0;; ++iteration) {
    if (iteration % poll == 0) {
      launch(1, StatusCountStage{p.status, p.environment_count, kPcgRunning, p.running});
      if (launch.fetch(p.running) == 0) return;
    }
    launch(p.unit_count, BlockProductStage{p, p.d, p.q});
    launch(p.unit_count, UnitDotStage{p.d, p.q, p.partial});
    launch(p.environment_count, EnvironmentDotStage{p, p.pap});
    launch(p.environment_count, StepLengthStage{p});
    launch(dofs, StepStage{p});
    launch_preconditioned_dots(launch, p, p.rz_next);
    launch(p.environment_count, NextDirectionStage{p});
    launch(dofs, DirectionStage{p, false});
  }
}

// A solve's structure, built on the host from a batch's pattern whenever it changes.
struct PcgStructure {
  std::vector<int> row, column;  // the pattern's blocks (all the solve reads of the pattern)
  BlockRows rows;
  JacobiBlocks jacobi;
  CoarseSpace coarse;
  std::vector<int> block_begin;       // environments + 1 offsets into the pattern's blocks
  std::vector<int> unit_environment;  // per unit
  std::vector<int> unit_begin;        // environments + 1 offsets
  int environment_count() const { return static_cast<int>(unit_begin.size()) - 1; }
};

// aggregate_vertices: FEM vertices per coarse aggregate; 0: block Jacobi alone.
PcgStructure pcg_structure(const FemBatch& fem, const AffineBatch& affine,
                           const BlockPattern& pattern, const std::vector<int>& dof_begin,
                           int aggregate_vertices);

// A solve's structure and work arrays in host (HostArray) or device (DeviceArray) memory.
template <template <class> class Array>
struct PcgStorage {
  explicit PcgStorage(const PcgStructure& s)
      : row(s.row),
        column(s.column),
        rows_begin(s.rows.begin),
        rows_entry(s.rows.entry),
        first_unit(s.jacobi.first_unit),
        jacobi_units(s.jacobi.units),
        matrix_block(s.jacobi.matrix_block),
        jacobi_begin(s.jacobi.environment_begin),
        unit_environment(s.unit_environment),
        unit_begin(s.unit_begin),
        status(std::size_t(s.environment_count())),
        iterations(std::size_t(s.environment_count())),
        running(std::size_t(1)),
        unit_aggregate(s.coarse.unit_aggregate),
        aggregate_unit_begin(s.coarse.aggregate_unit_begin),
        aggregate_unit(s.coarse.aggregate_unit),
        aggregate_begin(s.coarse.aggregate_begin),
        block_begin(s.block_begin),
        coarse_matrix_begin(s.coarse.matrix_begin),
        jacobi_ok(s.jacobi.units.size()),
        coarse_ok(std::size_t(s.environment_count())),
        vectors(12 * s.unit_environment.size()),
        scalars(8 * std::size_t(s.environment_count())),
        partial(s.unit_environment.size()),
        inverse(144 * s.jacobi.units.size()),
        coarse_matrix(std::size_t(s.coarse.matrix_begin.back())),
        coarse_vector(3 * std::size_t(s.coarse.aggregate_count())) {}

  // The buffers of a solve of the systems `block` (9 per pattern block) with these fixed DOFs
  // (per DOF), right-hand side, per-environment tolerances and solution x (the fixed DOFs'
  // values and the first guess on entry), all in this storage's memory.
  PcgBuffers buffers(const double* block, const char* fixed, const double* rhs,
                     const double* tolerance, int max_iterations, double* x) {
    PcgBuffers p;
    p.pattern = {
        static_cast<int>(row.size()), row.data(), column.data(), nullptr, nullptr, nullptr};
    p.block = block;
    p.rows = {rows_begin.data(), rows_entry.data()};
    p.jacobi = {static_cast<int>(jacobi_units.size()), first_unit.data(), jacobi_units.data(),
                matrix_block.data()};
    p.unit_count = static_cast<int>(unit_environment.size());
    p.unit_environment = unit_environment.data();
    p.fixed = fixed;
    p.environment_count = static_cast<int>(status.size());
    p.unit_begin = unit_begin.data();
    p.jacobi_begin = jacobi_begin.data();
    p.tolerance = tolerance;
    p.max_iterations = max_iterations;
    p.status = status.data();
    p.iterations = iterations.data();
    p.rhs = rhs;
    p.x = x;
    // Per DOF r, z, d, q one after another; per environment the eight scalars.
    double** const vector[4] = {&p.r, &p.z, &p.d, &p.q};
    for (int k = 0; k < 4; ++k) *vector[k] = vectors.data() + 3 * k * p.unit_count;
    double** const scalar[8] = {&p.residual, &p.rz,  &p.rz_next, &p.rr,
                                &p.rr0,      &p.pap, &p.alpha,   &p.beta};
    for (int k = 0; k < 8; ++k) *scalar[k] = scalars.data() + k * p.environment_count;
    p.partial = partial.data();
    p.jacobi_inverse = inverse.data();
    p.jacobi_ok = jacobi_ok.data();
    p.coarse = {static_cast<int>(aggregate_unit_begin.size()) - 1,
                unit_aggregate.data(),
                aggregate_unit_begin.data(),
                aggregate_unit.data(),
                aggregate_begin.data(),
                block_begin.data(),
                coarse_matrix_begin.data(),
                coarse_matrix.data(),
                coarse_vector.data(),
                coarse_ok.data()};
    p.running = running.data();
    return p;
  }

  // The bytes it holds.
  double bytes() const {
    return 4.0 * double(row.size() + column.size() + rows_begin.size() + rows_entry.size() +
                        first_unit.size() + jacobi_units.size() + matrix_block.size() +
                        jacobi_begin.size() + unit_environment.size() + unit_begin.size() +
                        status.size() + iterations.size() + running.size() + unit_aggregate.size() +
                        aggregate_unit_begin.size() + aggregate_unit.size() +
                        aggregate_begin.size() + block_begin.size()) +
           double(jacobi_ok.size() + coarse_ok.size()) +
           8.0 * double(vectors.size() + scalars.size() + partial.size() + inverse.size() +
                        coarse_matrix_begin.size() + coarse_matrix.size() + coarse_vector.size());
  }

  Array<int> row, column, rows_begin, rows_entry, first_unit, jacobi_units, matrix_block,
      jacobi_begin, unit_environment, unit_begin, status, iterations, running, unit_aggregate,
      aggregate_unit_begin, aggregate_unit, aggregate_begin, block_begin;
  Array<long long> coarse_matrix_begin;
  Array<char> jacobi_ok, coarse_ok;
  Array<double> vectors, scalars, partial, inverse, coarse_matrix, coarse_vector;
};

// A solve in host memory, for the host launchers.
class HostPcg {
 public:
  HostPcg(const FemBatch& fem, const AffineBatch& affine, const BlockPattern& pattern,
          const std::vector<int>& dof_begin, int aggregate_vertices = kCoarseAggregateVertices)
      : structure_(pcg_structure(fem, affine, pattern, dof_begin, aggregate_vertices)),
        storage_(structure_) {}

  // Solves the batch's systems with these blocks, fixed DOFs, right-hand side and per
  // environment tolerances; x holds the fixed DOFs' values and the first guess on entry. The
  // environments `skip` marks (per environment; null: none) are left as they are.
  template <class Launcher>
  void solve(Launcher& launch, const std::vector<double>& block, const std::vector<char>& fixed,
             const std::vector<double>& rhs, const std::vector<double>& tolerance,
             int max_iterations, std::vector<double>& x, const unsigned char* skip = nullptr) {
    check_sizes(block, fixed, rhs, tolerance, x);
    PcgBuffers p = storage_.buffers(block.data(), fixed.data(), rhs.data(), tolerance.data(),
                                    max_iterations, x.data());
    p.skip = skip;
    solve_block_pcg(launch, p);
  }

  const std::vector<int>& status() const { return storage_.status; }
  const std::vector<int>& iterations() const { return storage_.iterations; }
  // |r| / |r0| per environment at the end: the first of the scalars.
  std::vector<double> residual() const {
    return {storage_.scalars.begin(), storage_.scalars.begin() + structure_.environment_count()};
  }

 private:
  void check_sizes(const std::vector<double>& block, const std::vector<char>& fixed,
                   const std::vector<double>& rhs, const std::vector<double>& tolerance,
                   const std::vector<double>& x) const;

  PcgStructure structure_;
  PcgStorage<HostArray> storage_;
};

}  // namespace grip::solver::parallel
