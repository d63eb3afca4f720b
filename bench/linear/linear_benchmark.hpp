#pragma once
// `grip bench linear`: the direct solve (CHOLMOD, one core) against PETSc's KSP across the
// solver's ranks, on real Newton systems of growing size, to find where PETSc starts to pay.
#include <mpi.h>

#include <ostream>
#include <string>
#include <vector>

#include "farm/petsc/petsc_system_solver.hpp"

namespace grip::bench {

// Where the systems come from: a real bimanual soft trial (capture_bimanual_trial_system: a long
// bar, whose factor fills in little) or the bimanual squeeze (bimanual_squeeze: a cube, the
// worst case of fill for its size).
enum class LinearSystemSource { kBimanualTrial, kSqueeze };

struct LinearBenchmarkOptions {
  LinearSystemSource source = LinearSystemSource::kBimanualTrial;
  // Tet cell sizes (m) of the source's soft object, one system size each.
  std::vector<double> cells{0.01, 0.006, 0.004, 0.003, 0.0025};
  int repeats = 5;  // timed factorize + solve pairs per size and solver (after one untimed)
};

struct LinearBenchmarkRow {
  double cell = 0.0;
  int dofs = 0;
  long nonzeros = 0;          // of the whole symmetric matrix
  double direct_s = 0.0;      // median CHOLMOD numeric factorization + solve (symbolic reused)
  double direct_mib = 0.0;    // the most memory CHOLMOD held (factor and workspace), MiB
  double factor_mib = 0.0;    // the factor's values, MiB ([farm] petsc_min_factor_mib's measure)
  double factor_gflop = 0.0;  // one numeric factorization's floating-point operations, 10^9
  double petsc_s = 0.0;       // median PETSc factorize + solve (pattern and partition reused)
  int iterations = 0;         // of PETSc's last solve
  double relative_difference = 0.0;  // |x_petsc - x_direct| / |x_direct|
};

struct LinearBenchmarkResult {
  LinearSystemSource source = LinearSystemSource::kBimanualTrial;
  int ranks = 1;
  std::string method;  // PETSc's KSP and preconditioner
  std::vector<LinearBenchmarkRow> rows;
  // The fewest DOFs from which PETSc was faster at every larger size measured; 0 when it never
  // was.
  int crossover_dofs = 0;
  // Each rank's peak resident memory over the run (VmHWM), MiB: rank 0 captured the systems and
  // ran CHOLMOD and its share of PETSc; the others ran their share of PETSc only. Run one size
  // per process (--cells X) to read a size's own peak.
  std::vector<double> peak_rss_mib;
};

// Collective over `comm`, the solver's ranks: rank 0 builds the systems, times both solvers
// side by side and prints a table row to `out` as each size finishes, then stops `petsc`; the
// other ranks serve PETSc's solves and return an empty result. Every rank's peak memory
// reaches rank 0's result.
LinearBenchmarkResult run_linear_benchmark(farm::PetscSystemSolver& petsc,
                                           const LinearBenchmarkOptions& options, std::ostream& out,
                                           MPI_Comm comm);

// "bimanual-trial" or "squeeze", the command line's and the JSON's word for a source.
const char* to_string(LinearSystemSource source);

// The result as one JSON object on one line.
void write_json_line(std::ostream& out, const LinearBenchmarkResult& result);

}  // namespace grip::bench
