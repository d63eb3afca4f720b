// grip bench hard: the hard-case suite; exits non-zero when any case breaks an invariant.
#include <spdlog/spdlog.h>

#include <iostream>
#include <memory>
#include <stdexcept>

#include "app/cli/command_line.hpp"
#include "bench/app/commands.hpp"
#include "bench/hard/hard_benchmark.hpp"

namespace grip::commands {
namespace {

// grip bench hard [--cases ...] [--threads T] [--out DIR]: the hard-case suite, a pass/fail per
// invariant and statistics per case; non-zero exit when any case fails an invariant, its
// expected solver outcome or its physical check (bench/hard/, docs/results.md).
struct BenchHardArgs {
  std::vector<std::string> cases;  // empty: every case
  int threads = 0;                 // 0: all cores
  std::string out = "out/hard";
};

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

}  // namespace

void declare_bench_hard(cli::Command& group) {
  auto args = std::make_shared<BenchHardArgs>();
  cli::Command hard = group.subcommand(
      "hard", "Hard cases: a pass/fail per invariant (no intersection, no inversion)");
  hard.option("--cases", args->cases, "Cases (default: all)").list();
  hard.option("--threads", args->threads, "Threads (default: all cores)")
      .check(cli::Check::count());
  hard.option("--out", args->out, "Folder for the tables and plot")
      .show_default()
      .check(cli::Check::output_folder());
  hard.on_run([args] { return bench_hard(*args); });
}

}  // namespace grip::commands
