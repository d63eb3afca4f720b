#pragma once
// `grip bench scale`: the farm model (farm_model.hpp) fed with costs measured on this machine,
// checked against real mpirun runs at a few ranks, then run for a GRIP-sized job at 64 to
// 4,096 ranks: time to solution and parallel efficiency, as a table, a CSV and a plot.
#include <filesystem>
#include <string>
#include <vector>

#include "bench/scale/commit_probe.hpp"
#include "bench/scale/farm_model.hpp"

namespace grip::bench {

struct ScaleOptions {
  std::filesystem::path costs_file = "docs/results/trial/trial.csv";  // trial.csv or a dataset
  std::vector<std::string> grippers{"fin-ray"};
  std::uint64_t objects = 1200;
  std::uint64_t candidates = 100000;
  double soft_fraction = 0.5;
  std::uint64_t seed = 1;
  std::vector<int> ranks{64, 128, 256, 512, 1024, 2048, 4096};
  int batch = 4;          // candidates per work unit (one thread per rank: the farm's default)
  int round_batches = 4;  // the rounds what-if's work units per rank per round (the former default)
  FarmCosts costs;        // used where no measurement below replaces them
  // Rank counts to run the commit probe at under mpirun; it sets the claim and commit model.
  std::vector<int> measure;
  // A job to run under mpirun at `validate_ranks` (one thread per rank): its 1-rank run sets
  // the start-up and planning costs, every run is predicted and compared.
  std::filesystem::path validate_job;
  std::vector<int> validate_ranks{1, 2, 3};
  // What-ifs, each a scenario beside the farm's: "rounds" (the farm before per-unit commits),
  // "heaviest-first", "round-batches=N" (rounds of N units per rank), "batch=N".
  std::vector<std::string> what_if;
  std::filesystem::path out = "out/bench-scale";
  std::filesystem::path grip;     // the grip executable the runs start
  std::filesystem::path mpiexec;  // mpirun
};

struct ValidationRow {
  int ranks = 0;
  std::uint64_t trials = 0;
  double measured = 0;          // s, the whole mpirun
  double measured_farm = 0;     // s, planning + trial phase as the farm reports them
  double predicted_replay = 0;  // s, the model on this run's own trial costs
  double predicted_one = 0;     // s, the model on the 1-rank run's trial costs
};

struct ScaleRow {
  std::string scenario;  // "farm" or a what-if
  ModelRun run;
  double efficiency = 0;  // T(1) / (P T(P)), T(1): the farm's protocol on one rank
};

struct ScaleResult {
  FarmCosts costs;  // as used
  std::vector<ProbeResult> probes;
  std::vector<ValidationRow> validation;
  std::vector<ScaleRow> rows;
  double one_rank_seconds = 0;
  std::uint64_t trials = 0;
};

// Throws std::invalid_argument on bad options, std::runtime_error when a run fails. Writes
// <out>/scale.md, scale.csv, validation.csv and, with Debian's python3-matplotlib, scale.png.
ScaleResult run_scale(const ScaleOptions& options);

}  // namespace grip::bench
