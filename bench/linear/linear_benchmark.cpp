#include "bench/linear/linear_benchmark.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <stdexcept>
#include <string>
#include <utility>

#include "bench/linear/bimanual_squeeze.hpp"
#include "bench/linear/bimanual_trial_system.hpp"
#include "bench/linear/newton_system.hpp"
#include "solver/linear/sparse_cholesky.hpp"
#include "src/json/json_text.hpp"

namespace grip::bench {

namespace {

using Clock = std::chrono::steady_clock;

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t m = values.size() / 2;
  return values.size() % 2 ? values[m] : 0.5 * (values[m - 1] + values[m]);
}

// Runs `first` and `second` once untimed (the first run analyses the pattern), then `repeats`
// times each, timed and alternating, so both see the same load from whatever else runs.
template <typename A, typename B>
void time_side_by_side(int repeats, A first, B second, std::vector<double>& first_s,
                       std::vector<double>& second_s) {
  first();
  second();
  for (int r = 0; r < repeats; ++r) {
    Clock::time_point start = Clock::now();
    first();
    first_s.push_back(std::chrono::duration<double>(Clock::now() - start).count());
    start = Clock::now();
    second();
    second_s.push_back(std::chrono::duration<double>(Clock::now() - start).count());
  }
}

LinearBenchmarkRow measure(farm::PetscSystemSolver& petsc, LinearSystemSource source, double cell,
                           int repeats) {
  // The squeeze's first step already has contacts, and its pads are pinned, as in a trial.
  const NewtonSystem system = source == LinearSystemSource::kBimanualTrial
                                  ? capture_bimanual_trial_system(cell)
                                  : capture_newton_system(bimanual_squeeze(cell), 1);
  LinearBenchmarkRow row;
  row.cell = cell;
  row.dofs = static_cast<int>(system.lower.rows());
  row.nonzeros = 2 * system.lower.nonZeros() - system.lower.rows();
  solver::SparseCholesky cholesky;
  Eigen::VectorXd direct, iterative;
  std::vector<double> direct_s, petsc_s;
  time_side_by_side(
      repeats,
      [&] {
        if (!cholesky.factorize(system.lower)) throw std::runtime_error("CHOLMOD: not SPD");
        direct = cholesky.solve(system.rhs);
      },
      [&] {
        if (!petsc.factorize(system.lower) || !petsc.solve(system.rhs, iterative)) {
          throw std::runtime_error("PETSc: " + petsc.failure());
        }
      },
      direct_s, petsc_s);
  row.direct_s = median(direct_s);
  row.direct_mib = static_cast<double>(cholesky.peak_bytes()) / (1 << 20);
  row.factor_mib = static_cast<double>(cholesky.factor_bytes()) / (1 << 20);
  row.factor_gflop = cholesky.factor_flops() / 1e9;
  row.petsc_s = median(petsc_s);
  row.iterations = petsc.iterations();
  row.relative_difference = (iterative - direct).norm() / direct.norm();
  return row;
}

}  // namespace

const char* to_string(LinearSystemSource source) {
  return source == LinearSystemSource::kBimanualTrial ? "bimanual-trial" : "squeeze";
}

// This process's peak resident memory (VmHWM of /proc/self/status), MiB; 0 if unreadable.
double peak_rss_mib() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;  // kB
  }
  return 0.0;
}

// Every rank's peak_rss_mib(), on rank 0.
std::vector<double> gather_peak_rss(MPI_Comm comm) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  const double mine = peak_rss_mib();
  std::vector<double> all(rank == 0 ? ranks : 0);
  MPI_Gather(&mine, 1, MPI_DOUBLE, all.data(), 1, MPI_DOUBLE, 0, comm);
  return all;
}

LinearBenchmarkResult run_linear_benchmark(farm::PetscSystemSolver& petsc,
                                           const LinearBenchmarkOptions& options, std::ostream& out,
                                           MPI_Comm comm) {
  LinearBenchmarkResult result;
  result.source = options.source;
  result.ranks = petsc.ranks();
  if (petsc.rank() != 0) {
    petsc.serve();
    gather_peak_rss(comm);
    return result;
  }
  result.method = petsc.method();
  out << "Newton systems of the " << to_string(options.source) << "; PETSc " << result.method
      << " on " << result.ranks << " rank(s) against CHOLMOD on one core; median of "
      << options.repeats << " repeats\n"
      << "    cell m      DOFs    nonzeros  factor MiB  factor Gflop   direct s  direct MiB    "
         "PETSc s  iterations  rel. difference\n";
  try {
    for (const double cell : options.cells) {
      const LinearBenchmarkRow row = measure(petsc, options.source, cell, options.repeats);
      result.rows.push_back(row);
      out << std::setw(10) << cell << std::setw(10) << row.dofs << std::setw(12) << row.nonzeros
          << std::fixed << std::setprecision(1) << std::setw(12) << row.factor_mib << std::setw(14)
          << row.factor_gflop << std::setprecision(4) << std::setw(11) << row.direct_s
          << std::setprecision(1) << std::setw(12) << row.direct_mib << std::setprecision(4)
          << std::setw(11) << row.petsc_s << std::defaultfloat << std::setw(12) << row.iterations
          << std::setw(17) << std::setprecision(3) << row.relative_difference
          << std::setprecision(6) << std::endl;
    }
  } catch (...) {
    petsc.stop();  // let the serving ranks go before the error leaves
    gather_peak_rss(comm);
    throw;
  }
  petsc.stop();
  result.peak_rss_mib = gather_peak_rss(comm);
  out << "peak resident memory per rank (MiB):";
  for (const double mib : result.peak_rss_mib) out << ' ' << std::lround(mib);
  out << '\n';
  for (auto row = result.rows.rbegin(); row != result.rows.rend(); ++row) {
    if (row->petsc_s >= row->direct_s) break;
    result.crossover_dofs = row->dofs;
  }
  if (result.crossover_dofs > 0) {
    out << "PETSc is faster from " << result.crossover_dofs << " DOFs on\n";
  } else {
    out << "PETSc was not faster at the largest size measured: no crossover up to "
        << (result.rows.empty() ? 0 : result.rows.back().dofs) << " DOFs\n";
  }
  return result;
}

void write_json_line(std::ostream& out, const LinearBenchmarkResult& result) {
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (const LinearBenchmarkRow& row : result.rows) {
    rows.push_back(nlohmann::ordered_json{{"cell", row.cell},
                                          {"dofs", row.dofs},
                                          {"nonzeros", row.nonzeros},
                                          {"direct_s", row.direct_s},
                                          {"direct_mib", row.direct_mib},
                                          {"factor_mib", row.factor_mib},
                                          {"factor_gflop", row.factor_gflop},
                                          {"petsc_s", row.petsc_s},
                                          {"iterations", row.iterations},
                                          {"relative_difference", row.relative_difference}});
  }
  const nlohmann::ordered_json line = {{"benchmark", "linear"},
                                       {"system", to_string(result.source)},
                                       {"ranks", result.ranks},
                                       {"method", result.method},
                                       {"crossover_dofs", result.crossover_dofs},
                                       {"peak_rss_mib", result.peak_rss_mib},
                                       {"rows", std::move(rows)}};
  out << json::compact_text(line, "%.6g") << '\n';
}

}  // namespace grip::bench
