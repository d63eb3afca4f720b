// grip bench scaling: a farm job under mpirun at several rank and batch sizes
// (bench/scaling/scaling_benchmark.hpp, docs/farm.md).
#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <utility>

#include "bench/scaling/scaling_benchmark.hpp"
#include "src/app/commands.hpp"
#include "src/json/json_text.hpp"

namespace grip::commands {

int bench_scaling(const BenchScalingArgs& args) {
  bench::ScalingOptions options;
  options.job = args.job;
  options.ranks = args.ranks;
  options.envs = args.envs;
  options.threads = args.threads;
  options.repeats = args.repeats;
  options.out = args.out;
  options.grip = std::filesystem::read_symlink("/proc/self/exe");
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

}  // namespace grip::commands
