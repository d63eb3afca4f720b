#pragma once
// `grip bench scaling`: one farm job run under mpirun at every (ranks, batch size) setting,
// each setting several times with the settings interleaved (so the machine's noise falls on
// all of them alike); trials per second of the trial phase, median over the repeats, and the
// speedup against the first setting, as a table, a CSV and a plot.
#include <filesystem>
#include <string>
#include <vector>

namespace grip::bench {

struct ScalingOptions {
  std::filesystem::path job;
  std::vector<int> ranks{1, 2};
  std::vector<int> envs{0};  // candidates per batch; 0: the farm's default
  int threads = 0;           // per rank; 0: the farm's default
  int repeats = 3;
  std::filesystem::path out = "out/scaling";
  std::filesystem::path grip;     // the grip executable each run starts
  std::filesystem::path mpiexec;  // mpirun
};

struct ScalingRow {
  int ranks = 0;
  int envs = 0;              // as asked (0: default)
  int batch = 0;             // as the farm resolved it
  int threads = 0;           // per rank, as resolved
  int trials = 0;            // per run
  double trial_seconds = 0;  // median
  double total_seconds =
      0;  // median wall time of the whole mpirun (start-up and planning included)
  double trials_per_second = 0;  // trials / trial_seconds
  double speedup = 0;            // trials_per_second / the first row's
  std::vector<double> runs;      // trial seconds of every repeat
};

// Runs every setting; throws std::runtime_error naming the setting and its log when a run
// fails. Writes <out>/scaling.csv and <out>/scaling.md, and <out>/scaling.png when Debian's
// python3 with matplotlib is there.
std::vector<ScalingRow> run_scaling(const ScalingOptions& options);

}  // namespace grip::bench
