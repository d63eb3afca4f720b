// grip bench scaling: a farm job under mpirun at several rank and batch sizes
// (bench/scaling/scaling_benchmark.hpp, docs/farm.md).
#include <cstdio>
#include <filesystem>

#include "bench/scaling/scaling_benchmark.hpp"
#include "src/app/commands.hpp"

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
  std::printf("{\"job\": \"%s\", \"rows\": [", args.job.c_str());
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const bench::ScalingRow& r = rows[k];
    std::printf(
        "%s{\"ranks\": %d, \"threads\": %d, \"batch\": %d, \"trials\": %d, "
        "\"trial_seconds\": %.4f, \"trials_per_second\": %.4f, \"speedup\": %.4f}",
        k ? ", " : "", r.ranks, r.threads, r.batch, r.trials, r.trial_seconds, r.trials_per_second,
        r.speedup);
  }
  std::printf("]}\n");
  return 0;
}

}  // namespace grip::commands
