// grip bench robustness: solver failures on synthesized grasps over every object category
// (bench/robustness/robustness_benchmark.hpp, docs/results.md).
#include <spdlog/spdlog.h>

#include <cstdio>
#include <iostream>
#include <memory>
#include <stdexcept>

#include "app/cli/command_line.hpp"
#include "bench/app/commands.hpp"
#include "bench/robustness/robustness_benchmark.hpp"
#include "bench/robustness/robustness_report.hpp"

namespace grip::commands {
namespace {

// grip bench robustness [--grippers ...] [--categories ...] [--seeds N] [--candidates N]
// [--rigid] [--soft] [--threads T] [--out DIR]: solver failures on synthesized grasps over
// every object category; the counts are the result, so the exit code is 0 unless the inputs
// are bad (bench/robustness/, docs/results.md).
struct BenchRobustnessArgs {
  std::vector<std::string> grippers;    // empty: parallel-jaw, fin-ray, leap
  std::vector<std::string> categories;  // empty: every procedural category
  int seeds = 0;                        // shapes per category; 0: each gripper's default
  int candidates = 0;                   // per (object, gripper); 0: each gripper's default
  bool rigid = false;                   // only rigid objects (with soft, or neither: both)
  bool soft = false;                    // only soft objects
  int threads = 0;                      // 0: all cores
  std::string out = "out/robustness";
};

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

}  // namespace

void declare_bench_robustness(cli::Command& group) {
  auto args = std::make_shared<BenchRobustnessArgs>();
  cli::Command robustness = group.subcommand(
      "robustness", "Solver failures on synthesized grasps over every object category");
  robustness
      .option("--grippers", args->grippers, "Grippers: parallel-jaw, fin-ray, leap (default: all)")
      .list();
  robustness.option("--categories", args->categories, "Object categories (default: all)").list();
  robustness
      .option("--seeds", args->seeds,
              "Shapes per category: the first N seeds the gripper gets a candidate on "
              "(default: per gripper)")
      .check(cli::Check::positive_count());
  robustness
      .option("--candidates", args->candidates,
              "Candidates per object and gripper (default: per gripper)")
      .check(cli::Check::positive_count());
  robustness.flag("--rigid", args->rigid, "Rigid objects only");
  robustness.flag("--soft", args->soft, "Soft (FEM) objects only");
  robustness.option("--threads", args->threads, "Threads (default: all cores)")
      .check(cli::Check::count());
  robustness.option("--out", args->out, "Folder for robustness.md and robustness.csv")
      .show_default()
      .check(cli::Check::output_folder());
  robustness.on_run([args] { return bench_robustness(*args); });
}

}  // namespace grip::commands
