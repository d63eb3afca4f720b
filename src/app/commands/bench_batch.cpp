// grip bench batch: the batch engine's speedup over running environments one after another.
#include <spdlog/spdlog.h>

#include <iostream>

#include "bench/batch/batch_benchmark.hpp"
#include "src/app/commands.hpp"
#include "src/config/config.hpp"

namespace grip::commands {

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
  if (args.jitter >= 0) options.jitter = static_cast<std::uint64_t>(args.jitter);
  const bench::BatchBenchmarkResult result =
      bench::run_batch_benchmark(file, args.scene, options, std::cout);
  bench::write_json_line(std::cout, result);
  return 0;
}

}  // namespace grip::commands
