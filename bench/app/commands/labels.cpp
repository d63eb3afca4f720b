// grip bench labels: trial verdicts at the defaults against a refined reference
// (bench/labels/labels_benchmark.hpp, docs/results.md).
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <memory>
#include <stdexcept>

#include "app/cli/command_line.hpp"
#include "bench/app/commands.hpp"
#include "bench/labels/labels_benchmark.hpp"
#include "bench/labels/labels_report.hpp"

namespace grip::commands {
namespace {

struct BenchLabelsArgs {
  std::vector<std::string> arms;        // "gripper:rigid|soft"; empty: the benchmark's four
  std::vector<std::string> categories;  // empty: box, cylinder, capsule, bottle; all: every one
  int seeds = 2;                        // shapes per category
  int candidates = 4;                   // per shape
  int threads = 0;                      // 0: all cores
  std::string models = "coarse";        // coarse | production (LabelsOptions)
  // What the reference refines: any of dt, newton_tol, friction_lag, mesh, finger; empty: the
  // first three; none: no reference.
  std::vector<std::string> refine;
  int dt_divisor = 2;               // what refining dt divides it by
  double newton_tol = 0.0;          // the defaults' Newton tolerance; 0: the trial's
  int friction_lag_iterations = 0;  // the defaults' friction lag iterations; 0: the trial's
  double tet_growth = geometry::kSoftObjectInteriorGrowth;  // production soft objects
  bool full_trials = false;  // run decided trials to the end (LabelsOptions)
  std::string out = "out/labels";
};

int bench_labels(const BenchLabelsArgs& args) {
  bench::LabelsOptions options;
  options.categories = args.categories;
  options.seeds = args.seeds;
  options.candidates = args.candidates;
  options.threads = args.threads;
  options.production_models = args.models == "production";
  options.soft_interior_growth = args.tet_growth;
  // none: every flag stays off, and no reference runs.
  const bool none = std::find(args.refine.begin(), args.refine.end(), "none") != args.refine.end();
  if (none && args.refine.size() > 1) {
    spdlog::error("grip bench labels: --refine none runs no reference; give it alone");
    return 2;
  }
  options.refinement.dt = args.refine.empty();
  options.refinement.newton_tol = args.refine.empty();
  options.refinement.friction_lag = args.refine.empty();
  for (const std::string& r : args.refine) {
    options.refinement.dt = options.refinement.dt || r == "dt";
    options.refinement.newton_tol = options.refinement.newton_tol || r == "newton_tol";
    options.refinement.friction_lag = options.refinement.friction_lag || r == "friction_lag";
    options.refinement.mesh = options.refinement.mesh || r == "mesh";
    options.refinement.finger = options.refinement.finger || r == "finger";
  }
  options.refinement.dt_divisor = args.dt_divisor;
  if (args.newton_tol > 0.0) options.defaults.sim.newton_tol = args.newton_tol;
  if (args.friction_lag_iterations > 0) {
    options.defaults.sim.friction_lag_iterations = args.friction_lag_iterations;
  }
  options.full_trials = args.full_trials;
  options.out = args.out;
  try {
    for (const std::string& arm : args.arms) options.arms.push_back(bench::parse_labels_arm(arm));
  } catch (const std::invalid_argument& e) {
    spdlog::error("grip bench labels: {}", e.what());
    return 2;
  }
  try {
    bench::check_labels_options(options);
  } catch (const std::invalid_argument& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
  const bench::LabelsResult result = bench::run_labels(options);
  const std::vector<bench::LabelsArmTally> tallies = bench::labels_tallies(result);
  std::cout << "\n";
  bench::write_labels_table(std::cout, tallies);
  bench::write_labels_files(options.out, result, tallies);
  std::printf("tables: %s/labels.md, candidates: %s/labels.csv\n", args.out.c_str(),
              args.out.c_str());
  bench::write_labels_json_line(std::cout, result, tallies);
  return 0;
}

}  // namespace

void declare_bench_labels(cli::Command& group) {
  auto args = std::make_shared<BenchLabelsArgs>();
  cli::Command labels = group.subcommand(
      "labels", "Trial verdicts at the defaults against a refined reference (dt/2, ...)");
  labels
      .option("--arms", args->arms,
              "Gripper and object model, e.g. fin-ray:soft,leap:rigid (default: "
              "parallel-jaw:rigid,fin-ray:rigid,fin-ray:soft,leap:rigid)")
      .list();
  labels
      .option("--categories", args->categories,
              "Object categories, or all for every one of the library (default: "
              "box,cylinder,capsule,bottle)")
      .list();
  labels.option("--seeds", args->seeds, "Shapes per category")
      .check(cli::Check::positive_count())
      .show_default();
  labels.option("--candidates", args->candidates, "Candidates per shape")
      .check(cli::Check::positive_count())
      .show_default();
  labels.option("--threads", args->threads, "Threads (default: all cores)")
      .check(cli::Check::count());
  labels
      .option("--models", args->models,
              "coarse: the robustness benchmark's (1-layer fin-ray, capsule hand, coarser "
              "soft objects); production: the models grip trial simulates")
      .show_default()
      .check(cli::Check::one_of({"coarse", "production"}));
  labels
      .option("--refine", args->refine,
              "What the reference refines (default: the first three): dt (halved), "
              "newton_tol (/10), friction_lag (one more iteration), mesh (soft objects "
              "meshed uniformly inside), finger (the fin-ray finger meshed finer); none: no "
              "reference, the defaults' verdicts and closing forces alone")
      .list()
      .check(cli::Check::one_of({"dt", "newton_tol", "friction_lag", "mesh", "finger", "none"}));
  labels.flag("--full-trials", args->full_trials,
              "Run every trial through the six gravity phases, also once its verdict is decided");
  labels
      .option("--dt-divisor", args->dt_divisor,
              "What the reference divides dt by (a convergence study's 4, 8, ...)")
      .show_default()
      .check(cli::Check::range(2, 64));
  labels
      .option("--newton-tol", args->newton_tol,
              "The defaults' Newton tolerance (default: the trial's, 1e-3)")
      .check(cli::Check::positive());
  labels
      .option("--friction-lag", args->friction_lag_iterations,
              "The defaults' friction lag iterations (default: the trial's, 1)")
      .check(cli::Check::positive_count());
  labels
      .option("--tet-growth", args->tet_growth,
              "Production soft objects: tets grow with depth (grip trial --tet-growth)")
      .show_default()
      .check(cli::Check::range(0.0, geometry::kMaxInteriorGrowth));
  labels.option("--out", args->out, "Folder for labels.md and labels.csv")
      .show_default()
      .check(cli::Check::output_folder());
  labels.on_run([args] { return bench_labels(*args); });
}

}  // namespace grip::commands
