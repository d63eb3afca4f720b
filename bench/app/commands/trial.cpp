// grip bench trial: what one grasp trial costs per gripper x object model, by solver stage
// (bench/trial/trial_benchmark.hpp, docs/results.md).
#include <spdlog/spdlog.h>

#include <cstdio>
#include <iostream>
#include <memory>
#include <stdexcept>

#include "app/cli/command_line.hpp"
#include "bench/app/commands.hpp"
#include "bench/trial/trial_benchmark.hpp"
#include "bench/trial/trial_report.hpp"

namespace grip::commands {
namespace {

// grip bench trial [--arms ...] [--categories ...] [--candidates N] [--repeats N]
// [--no-reference] [--out DIR]: what one grasp trial costs per gripper x object model, by solver
// stage, one trial at a time on one thread (bench/trial/, docs/results.md).
struct BenchTrialArgs {
  std::vector<std::string> arms;        // "gripper:rigid|soft"; empty: the benchmark's five
  std::vector<std::string> categories;  // empty: box, cylinder, capsule, bottle
  int candidates = 0;                   // per arm; 0: the arm's default
  int repeats = 3;                      // runs of each candidate at the defaults (median)
  bool no_reference = false;            // skip the runs at the reference
  std::string models = "production";    // production | coarse (TrialBenchOptions)
  std::string out = "out/bench-trial";
};

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

}  // namespace

void declare_bench_trial(cli::Command& group) {
  auto args = std::make_shared<BenchTrialArgs>();
  cli::Command trial = group.subcommand(
      "trial", "What one grasp trial costs per gripper x object model, by solver stage");
  trial
      .option("--arms", args->arms,
              "Gripper and object model, e.g. fin-ray:soft,leap:rigid (default: "
              "parallel-jaw:rigid,fin-ray:rigid,fin-ray:soft,leap:rigid,leap:soft)")
      .list();
  trial
      .option("--categories", args->categories,
              "Object categories (default: box,cylinder,capsule,bottle)")
      .list();
  trial
      .option("--candidates", args->candidates,
              "Candidates per arm (default: 8 parallel-jaw:rigid, 4 leap:rigid, 2 others)")
      .check(cli::Check::positive_count());
  trial.option("--repeats", args->repeats, "Runs per candidate at the defaults")
      .show_default()
      .check(cli::Check::positive_count());
  trial.flag("--no-reference", args->no_reference,
             "Skip the runs at the reference (dt/2, newton_tol/10, two lag iterations)");
  trial
      .option("--models", args->models,
              "production: the models grip trial simulates; coarse: the robustness "
              "benchmark's (1-layer fin-ray, capsule hand, coarser soft objects)")
      .show_default()
      .check(cli::Check::one_of({"production", "coarse"}));
  trial.option("--out", args->out, "Folder for trial.md and trial.csv")
      .show_default()
      .check(cli::Check::output_folder());
  trial.on_run([args] { return bench_trial(*args); });
}

}  // namespace grip::commands
