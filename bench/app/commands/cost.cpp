// grip bench cost: what a farm pays per synthesized candidate, by verdict, in CPU seconds and in
// units of a fixed CHOLMOD factorization (bench/cost/cost_benchmark.hpp, docs/results.md).
#include <cstdio>
#include <iostream>
#include <memory>

#include "app/cli/command_line.hpp"
#include "bench/app/commands.hpp"
#include "bench/cost/cost_benchmark.hpp"
#include "bench/cost/cost_report.hpp"
#include "bench/cost/cost_statistics.hpp"
#include "src/objects/object_library.hpp"

namespace grip::commands {
namespace {

// grip bench cost [--grippers ...] [--categories ...] [--seeds N] [--candidates N]
// [--rigid] [--soft] [--coarse] [--full-trials] [--reference-repeats N] [--out DIR]: each
// synthesized candidate alone, its CPU seconds by verdict; the figures are the result, so the exit
// code is 0 unless the inputs are bad (bench/cost/, docs/results.md).
struct BenchCostArgs {
  std::vector<std::string> grippers;    // empty: parallel-jaw, fin-ray, leap
  std::vector<std::string> categories;  // empty: box, cylinder, capsule, bottle
  int seeds = 1;
  int candidates = 8;
  bool rigid = false;   // with --soft: both; neither: rigid only
  bool soft = false;    // alone: soft only
  bool coarse = false;  // the robustness benchmark's coarse models instead of production's
  int reference_repeats = 9;
  bool full_trials = false;  // run decided trials to the end (CostOptions)
  std::string out = "out/cost";
};

int bench_cost(const BenchCostArgs& args) {
  bench::CostOptions options;
  options.grippers = args.grippers;
  options.categories = args.categories;
  options.seeds = args.seeds;
  options.candidates = args.candidates;
  options.rigid = args.rigid || !args.soft;
  options.soft = args.soft;
  options.production_models = !args.coarse;
  options.reference_repeats = args.reference_repeats;
  options.full_trials = args.full_trials;
  options.out = args.out;
  const bench::CostResult result = bench::run_cost(options);
  const std::vector<bench::CostRow> rows = bench::cost_rows(result);
  std::cout << "\n";
  bench::write_cost_table(std::cout, rows);
  bench::write_cost_files(options.out, result, rows);
  std::printf("tables: %s/cost.md, candidates: %s/cost.csv\n", args.out.c_str(), args.out.c_str());
  bench::write_cost_json_line(std::cout, result, rows);
  return 0;
}

std::vector<std::string> category_names() {
  std::vector<std::string> names;
  for (const objects::ObjectCategory c : objects::all_object_categories()) {
    names.emplace_back(objects::category_name(c));
  }
  return names;
}

}  // namespace

void declare_bench_cost(cli::Command& group) {
  auto args = std::make_shared<BenchCostArgs>();
  cli::Command cost = group.subcommand(
      "cost", "What a farm pays per synthesized candidate, by verdict (CPU s, reference units)");
  cost.option("--grippers", args->grippers, "Grippers (default: parallel-jaw,fin-ray,leap)")
      .list()
      .check(cli::Check::one_of(bench::kCostGrippers));
  cost.option("--categories", args->categories,
              "Object categories (default: box,cylinder,capsule,bottle)")
      .list()
      .check(cli::Check::one_of(category_names()));
  cost.option("--seeds", args->seeds,
              "Shapes per category: the first N seeds the gripper gets a candidate on")
      .show_default()
      .check(cli::Check::positive_count());
  cost.option("--candidates", args->candidates, "Candidates synthesized per shape")
      .show_default()
      .check(cli::Check::positive_count());
  cost.flag("--rigid", args->rigid, "Rigid objects (the default; with --soft, both)");
  cost.flag("--soft", args->soft, "Soft (FEM) objects: minutes per trial (alone: soft only)");
  cost.flag("--full-trials", args->full_trials,
            "Run every trial through the six gravity phases, also once its verdict is decided");
  cost.flag("--coarse", args->coarse,
            "The robustness benchmark's coarse models (1-layer fin-ray, capsule hand, coarser "
            "soft objects) instead of the production ones the farm simulates");
  cost.option("--reference-repeats", args->reference_repeats,
              "Reference factorizations timed at the start, and again at the end")
      .show_default()
      .check(cli::Check::positive_count());
  cost.option("--out", args->out, "Folder for cost.md and cost.csv")
      .show_default()
      .check(cli::Check::output_folder());
  cost.on_run([args] { return bench_cost(*args); });
}

}  // namespace grip::commands
