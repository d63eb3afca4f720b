// grip bench model: what modelling only what a scene needs saves, in time and error
// (bench/model/model_benchmark.hpp, docs/results.md).
#include <spdlog/spdlog.h>

#include <cstdio>
#include <filesystem>
#include <iostream>

#include "bench/model/model_benchmark.hpp"
#include "src/app/commands.hpp"

namespace grip::commands {

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

}  // namespace grip::commands
