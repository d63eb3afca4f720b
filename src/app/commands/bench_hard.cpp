// grip bench hard: the hard-case suite; exits non-zero when any case breaks an invariant.
#include <spdlog/spdlog.h>

#include <iostream>
#include <stdexcept>

#include "bench/hard/hard_benchmark.hpp"
#include "src/app/commands.hpp"

namespace grip::commands {

int bench_hard(const BenchHardArgs& args) {
  bench::HardBenchmarkOptions options;
  options.cases = args.cases;
  options.threads = args.threads;
  options.out = args.out;
  try {
    const auto results = bench::run_hard_benchmark(options, std::cout);
    spdlog::info("tables and plot in {}", options.out.string());
    return bench::all_passed(results) ? 0 : 1;
  } catch (const std::invalid_argument& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
}

}  // namespace grip::commands
