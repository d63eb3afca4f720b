// grip bench model: what modelling only what a scene needs saves, in time and error
// (bench/model/model_benchmark.hpp, docs/results.md).
#include <spdlog/spdlog.h>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include "app/cli/command_line.hpp"
#include "bench/app/commands.hpp"
#include "bench/model/model_benchmark.hpp"

namespace grip::commands {
namespace {

// grip bench model [--repeats N] [--threads T] [--out DIR]: what modelling only what a scene
// needs saves, in time and error (bench/model/, docs/results.md).
struct BenchModelArgs {
  int repeats = 5;  // runs per variant; the table reports the median
  int threads = 1;
  std::string out = "out/model";
};

int bench_model(const BenchModelArgs& args) {
  bench::ModelBenchmarkOptions options;
  options.repeats = args.repeats;
  options.threads = args.threads;
  const std::vector<bench::ModelComparison> comparisons =
      bench::run_model_benchmark(options, std::cout);
  std::cout << "\n";
  bench::write_model_table(std::cout, comparisons);
  const bool plotted = bench::write_model_outputs(args.out, comparisons, options);
  std::printf("table: %s/model.md, %s/model.csv%s\n", args.out.c_str(), args.out.c_str(),
              plotted ? ", plot: model.png" : "");
  for (const bench::ModelComparison& c : comparisons) {
    if (!c.failure.empty()) return 1;
  }
  return 0;
}

}  // namespace

void declare_bench_model(cli::Command& group) {
  auto args = std::make_shared<BenchModelArgs>();
  cli::Command model = group.subcommand(
      "model", "What modelling only what a scene needs saves: time and error per choice");
  model.option("--repeats", args->repeats, "Runs per variant (median)")
      .show_default()
      .check(cli::Check::positive_count());
  model.option("--threads", args->threads, "Threads")
      .show_default()
      .check(cli::Check::positive_count());
  model.option("--out", args->out, "Folder for tables and plots")
      .show_default()
      .check(cli::Check::output_folder());
  model.on_run([args] { return bench_model(*args); });
}

}  // namespace grip::commands
