// grip bench accuracy: work-precision of the solver's settings on the standard trial scenes
// (bench/accuracy/accuracy_benchmark.hpp, docs/results.md).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/cli/command_line.hpp"
#include "bench/accuracy/accuracy_benchmark.hpp"
#include "bench/app/commands.hpp"

namespace grip::commands {
namespace {

// grip bench accuracy [--scenes ...] [--sweeps ...] [--threads T] [--repeats N] [--out DIR]:
// work-precision of the solver's settings on the standard trial scenes against a tight
// reference run (bench/accuracy/, docs/results.md).
struct BenchAccuracyArgs {
  std::vector<std::string> scenes;  // empty: every standard scene
  std::vector<std::string> sweeps;  // settings to sweep; empty: all
  int threads = 0;                  // 0: all cores
  int repeats = 1;                  // runs per setting; the wall time is their median
  std::string out = "out/accuracy";
};

// Millimetres (milliradians) to three significant digits, "n/a" for NaN.
void print_milli(double v) {
  if (std::isnan(v)) {
    std::printf(" %9s", "n/a");
  } else {
    std::printf(" %9.3g", 1e3 * v);
  }
}

int bench_accuracy(const BenchAccuracyArgs& args) {
  bench::AccuracyOptions options;
  options.scenes = args.scenes;
  options.sweeps = args.sweeps;
  options.threads = args.threads;
  options.repeats = args.repeats;
  options.out = args.out;
  const std::vector<bench::AccuracyRow> rows = bench::run_accuracy(options);

  std::printf("%-16s %-24s %9s %9s %9s %9s %9s %9s %9s %8s %6s\n", "scene", "sweep", "value",
              "wall(s)", "newton", "pose(mm)", "rot(mrad)", "slip(mm)", "vert(mm)", "verdicts",
              "front");
  for (const bench::AccuracyRow& r : rows) {
    const bool reference = r.sweep == "reference";
    std::printf("%-16s %-24s %9.3g %9.2f %9llu", r.scene.c_str(), r.sweep.c_str(),
                reference ? 0.0 : r.value, r.seconds,
                static_cast<unsigned long long>(r.newton_iterations));
    for (double e : {r.error.translation, r.error.rotation, r.error.slip, r.error.vertices})
      print_milli(reference ? 0.0 : e);
    std::printf(" %6d/%d %6s%s\n", r.error.agreeing, r.error.candidates,
                reference          ? ""
                : r.on_sweep_front ? "yes"
                                   : "no",
                r.is_default ? "  (default)" : "");
  }
  const std::filesystem::path out = args.out;
  std::printf("tables: %s, %s%s\n", (out / "accuracy.md").c_str(), (out / "accuracy.csv").c_str(),
              std::filesystem::exists(out / "accuracy.png")
                  ? ", plots: accuracy.png, accuracy_iterations.png"
                  : "");
  return 0;
}

}  // namespace

void declare_bench_accuracy(cli::Command& group) {
  auto args = std::make_shared<BenchAccuracyArgs>();
  cli::Command accuracy = group.subcommand(
      "accuracy", "Work-precision of the solver's settings against a tight reference run");
  accuracy
      .option("--scenes", args->scenes,
              "Scenes: fin-ray-rigid, fin-ray-soft, hand-rigid (default: all)")
      .list();
  accuracy
      .option("--sweeps", args->sweeps,
              "Settings: dt, newton_tol, d_hat, kappa, eps_v, friction_lag_iterations, "
              "mesh (default: all)")
      .list();
  accuracy.option("--threads", args->threads, "Threads (default: all cores)")
      .check(cli::Check::count());
  accuracy.option("--repeats", args->repeats, "Runs per setting (median)")
      .show_default()
      .check(cli::Check::positive_count());
  accuracy.option("--out", args->out, "Folder for tables and plots")
      .show_default()
      .check(cli::Check::output_folder());
  accuracy.on_run([args] { return bench_accuracy(*args); });
}

}  // namespace grip::commands
