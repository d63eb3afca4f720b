// grip bench labels: trial verdicts at the defaults against a refined reference
// (bench/labels/labels_benchmark.hpp, docs/results.md).
#include <spdlog/spdlog.h>

#include <cstdio>
#include <iostream>
#include <stdexcept>

#include "bench/labels/labels_benchmark.hpp"
#include "bench/labels/labels_report.hpp"
#include "src/app/commands.hpp"

namespace grip::commands {

int bench_labels(const BenchLabelsArgs& args) {
  bench::LabelsOptions options;
  options.categories = args.categories;
  options.seeds = args.seeds;
  options.candidates = args.candidates;
  options.threads = args.threads;
  options.production_models = args.models == "production";
  options.soft_interior_growth = args.tet_growth;
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

}  // namespace grip::commands
