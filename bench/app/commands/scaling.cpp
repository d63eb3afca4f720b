// grip bench scaling: a farm job under mpirun at several rank and batch sizes
// (bench/scaling/scaling_benchmark.hpp, docs/farm.md).
#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <utility>

#include "app/cli/command_line.hpp"
#include "bench/app/commands.hpp"
#include "bench/scaling/scaling_benchmark.hpp"
#include "src/json/json_text.hpp"

namespace grip::commands {
namespace {

// grip bench scaling JOB.toml [--ranks 1,2] [--envs 4,8] [--threads T] [--repeats N] --out DIR:
// the job under mpirun at each rank and batch size; trials per second and speedup as a table
// and a plot (bench/scaling/, docs/farm.md).
struct BenchScalingArgs {
  std::string job;
  std::vector<int> ranks{1, 2};
  std::vector<int> envs{0};  // candidates per batch; 0: the farm's default
  int threads = 0;           // per rank; 0: the farm's default (the node's cores shared)
  int repeats = 3;           // runs per setting; the table reports the median
  std::string out = "out/scaling";
};

int bench_scaling(const BenchScalingArgs& args) {
  bench::ScalingOptions options;
  options.job = args.job;
  options.ranks = args.ranks;
  options.envs = args.envs;
  options.threads = args.threads;
  options.repeats = args.repeats;
  options.out = args.out;
  options.grip = cli::sibling_program("grip");
  options.mpiexec = GRIP_MPIEXEC;
  const std::vector<bench::ScalingRow> rows = bench::run_scaling(options);

  std::printf("%6s %8s %6s %7s %12s %10s %10s %8s\n", "ranks", "threads", "batch", "trials",
              "trials (s)", "whole (s)", "trials/s", "speedup");
  for (const bench::ScalingRow& r : rows) {
    std::printf("%6d %8d %6d %7d %12.2f %10.2f %10.3f %7.2fx\n", r.ranks, r.threads, r.batch,
                r.trials, r.trial_seconds, r.total_seconds, r.trials_per_second, r.speedup);
  }
  std::printf("table: %s/scaling.md, %s/scaling.csv%s\n", args.out.c_str(), args.out.c_str(),
              std::filesystem::exists(options.out / "scaling.png") ? ", plot: scaling.png" : "");
  nlohmann::ordered_json summary_rows = nlohmann::ordered_json::array();
  for (const bench::ScalingRow& r : rows) {
    summary_rows.push_back(nlohmann::ordered_json{{"ranks", r.ranks},
                                                  {"threads", r.threads},
                                                  {"batch", r.batch},
                                                  {"trials", r.trials},
                                                  {"trial_seconds", r.trial_seconds},
                                                  {"trials_per_second", r.trials_per_second},
                                                  {"speedup", r.speedup}});
  }
  const nlohmann::ordered_json summary = {{"job", args.job}, {"rows", std::move(summary_rows)}};
  std::printf("%s\n", json::text(summary, "%.4f").c_str());
  return 0;
}

}  // namespace

void declare_bench_scaling(cli::Command& group) {
  auto args = std::make_shared<BenchScalingArgs>();
  cli::Command scaling = group.subcommand(
      "scaling",
      "A farm job under mpirun at several rank and batch sizes: trials/s, speedup, plot");
  scaling.option("job", args->job, "Job file (e.g. jobs/scaling.toml)").required();
  scaling.option("--ranks", args->ranks, "MPI rank counts, e.g. 1,2,4")
      .list()
      .check(cli::Check::positive_count());
  scaling
      .option("--envs", args->envs,
              "Candidates per batch (environments at once), e.g. 2,8; 0: default")
      .list()
      .check(cli::Check::count());
  scaling
      .option("--threads", args->threads,
              "Threads per rank (default: the node's cores shared by its ranks)")
      .check(cli::Check::count());
  scaling.option("--repeats", args->repeats, "Runs per setting (median)")
      .show_default()
      .check(cli::Check::positive_count());
  scaling
      .option("--out", args->out,
              "Folder for the datasets, table (scaling.md, scaling.csv) and plot")
      .show_default()
      .check(cli::Check::output_folder());
  scaling.on_run([args] { return bench_scaling(*args); });
}

}  // namespace grip::commands
