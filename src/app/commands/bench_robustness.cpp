// grip bench robustness: solver failures on synthesized grasps over every object category
// (bench/robustness/robustness_benchmark.hpp, docs/results.md).
#include <spdlog/spdlog.h>

#include <cstdio>
#include <iostream>
#include <stdexcept>

#include "bench/robustness/robustness_benchmark.hpp"
#include "bench/robustness/robustness_report.hpp"
#include "src/app/commands.hpp"

namespace grip::commands {

int bench_robustness(const BenchRobustnessArgs& args) {
  bench::RobustnessOptions options;
  options.grippers = args.grippers;
  options.categories = args.categories;
  options.seeds = args.seeds;
  options.candidates = args.candidates;
  // --rigid or --soft alone picks one kind; both or neither run both.
  if (args.rigid != args.soft) {
    options.rigid = args.rigid;
    options.soft = args.soft;
  }
  options.threads = args.threads;
  options.out = args.out;
  try {
    bench::plan_robustness(options);
  } catch (const std::invalid_argument& e) {
    spdlog::error("grip bench robustness: {}", e.what());
    return 2;
  }
  const bench::RobustnessResult result = bench::run_robustness(options);
  const std::vector<bench::RobustnessTally> rows = bench::robustness_rows(result);
  std::cout << "\n";
  bench::write_robustness_table(std::cout, rows);
  bench::write_robustness_files(options.out, result, rows);
  std::printf("table: %s/robustness.md, trials: %s/robustness.csv\n", args.out.c_str(),
              args.out.c_str());
  bench::write_robustness_json_line(std::cout, result, rows);
  return 0;
}

}  // namespace grip::commands
