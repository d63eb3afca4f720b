// grip bench batch: the batch engine's speedup over running environments one after another.
#include <spdlog/spdlog.h>

#include <iostream>
#include <memory>

#include "app/cli/command_line.hpp"
#include "app/cli/device_option.hpp"
#include "bench/app/commands.hpp"
#include "bench/batch/batch_benchmark.hpp"
#include "src/config/config.hpp"

namespace grip::commands {
namespace {

// grip bench batch --scene S.toml [--envs 1,2,4,...] [--threads T] [--device cpu|host]
// [--jitter SEED]: N copies of a scene one after another and as one batch.
struct BenchBatchArgs {
  std::string scene;
  std::vector<int> envs{1, 2, 4, 8, 16, 32, 64};
  int threads = 0;             // 0: all cores
  std::string device = "cpu";  // the engine: cpu, host (data-parallel) or cuda
  std::int64_t jitter = -1;    // seed; < 0: no jitter
};

int bench_batch(const BenchBatchArgs& args) {
  scene::SceneFile file;
  try {
    file = scene::load_scene_file(args.scene);
  } catch (const config::ConfigError& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  bench::BatchBenchmarkOptions options;
  options.envs = args.envs;
  options.threads = args.threads;
  options.device = solver::engine_device(args.device);
  if (args.jitter >= 0) options.jitter = static_cast<std::uint64_t>(args.jitter);
  const bench::BatchBenchmarkResult result =
      bench::run_batch_benchmark(file, args.scene, options, std::cout);
  bench::write_json_line(std::cout, result);
  return 0;
}

}  // namespace

void declare_bench_batch(cli::Command& group) {
  auto args = std::make_shared<BenchBatchArgs>();
  cli::Command batch = group.subcommand(
      "batch", "N copies of a scene one after another and as one batch: speedup, memory");
  batch.option("--scene", args->scene, "Scene file (docs/scene-format.md)").required();
  batch.option("--envs", args->envs, "Environment counts, e.g. 1,2,4,8")
      .list()
      .check(cli::Check::positive_count());
  batch.option("--threads", args->threads, "Threads (default: all cores)")
      .check(cli::Check::count());
  batch.option("--device", args->device, cli::device_help())
      .show_default()
      .check(cli::device_check());
  batch.on_check([args] { cli::refuse_cuda_device(args->device); });
  batch
      .option("--jitter", args->jitter,
              "Seed: move each copy's free bodies by up to d_hat/4 per axis")
      .check(cli::Check::count());
  batch.on_run([args] { return bench_batch(*args); });
}

}  // namespace grip::commands
