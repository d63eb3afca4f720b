// grip bench trial: what one grasp trial costs per gripper x object model, by solver stage
// (bench/trial/trial_benchmark.hpp, docs/results.md).
#include <spdlog/spdlog.h>

#include <cstdio>
#include <iostream>
#include <stdexcept>

#include "bench/trial/trial_benchmark.hpp"
#include "bench/trial/trial_report.hpp"
#include "src/app/commands.hpp"

namespace grip::commands {

int bench_trial(const BenchTrialArgs& args) {
  bench::TrialBenchOptions options;
  options.categories = args.categories;
  options.candidates = args.candidates;
  options.repeats = args.repeats;
  options.reference = !args.no_reference;
  options.production_models = args.models == "production";
  options.out = args.out;
  try {
    for (const std::string& arm : args.arms) options.arms.push_back(bench::parse_labels_arm(arm));
  } catch (const std::invalid_argument& e) {
    spdlog::error("grip bench trial: {}", e.what());
    return 2;
  }
  try {
    bench::check_trial_bench_options(options);
  } catch (const std::invalid_argument& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
  const bench::TrialBenchResult result = bench::run_trial_bench(options);
  const std::vector<bench::TrialBenchSummary> summaries = bench::trial_bench_summaries(result);
  std::cout << "\n";
  bench::write_trial_bench_tables(std::cout, summaries);
  bench::write_trial_bench_files(options.out, result, summaries);
  std::printf("tables: %s/trial.md, runs: %s/trial.csv\n", args.out.c_str(), args.out.c_str());
  bench::write_trial_bench_json_line(std::cout, result, summaries);
  return 0;
}

}  // namespace grip::commands
