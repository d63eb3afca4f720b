#include "bench/labels/labels_benchmark.hpp"

#include <spdlog/spdlog.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <stdexcept>

namespace grip::bench {

LabelsArm parse_labels_arm(const std::string& text) {
  const std::size_t colon = text.find(':');
  const std::string model = colon == std::string::npos ? "" : text.substr(colon + 1);
  if (model != "rigid" && model != "soft") {
    throw std::invalid_argument("--arms '" + text + "': write gripper:rigid or gripper:soft");
  }
  return {text.substr(0, colon), model == "soft"};
}

std::string labels_arm_name(const LabelsArm& arm) {
  return arm.gripper + " x " + (arm.soft ? "soft" : "rigid");
}

std::vector<std::string> labels_categories(const LabelsOptions& options) {
  if (options.categories.empty()) return kLabelsCategories;
  if (options.categories != std::vector<std::string>{"all"}) return options.categories;
  return robustness_categories({});
}

trial::TrialParameters reference_parameters(const trial::TrialParameters& defaults,
                                            const LabelsRefinement& refinement) {
  trial::TrialParameters p = defaults;
  if (refinement.dt) {
    const int k = refinement.dt_divisor;
    p.sim.dt = defaults.sim.dt / k;
    p.settle_steps = k * defaults.settle_steps;
    p.settle_max_steps = k * defaults.settle_max_steps;
    p.displacement_factor = k * defaults.displacement_factor;
  }
  if (refinement.newton_tol) p.sim.newton_tol = defaults.sim.newton_tol / 10;
  if (refinement.friction_lag)
    p.sim.friction_lag_iterations = defaults.sim.friction_lag_iterations + 1;
  return p;
}

namespace {

RobustnessOptions arm_options(const LabelsOptions& options, const LabelsArm& arm,
                              const trial::TrialParameters& parameters, bool reference) {
  const bool uniform_mesh = reference && options.refinement.mesh;
  RobustnessOptions o;
  o.grippers = {arm.gripper};
  o.categories = labels_categories(options);
  o.seeds = options.seeds;
  o.candidates = options.candidates;
  o.rigid = !arm.soft;
  o.soft = arm.soft;
  o.parameters = parameters;
  o.threads = options.threads;
  o.full_trials = options.full_trials;
  o.production_models = options.production_models;
  o.soft_interior_growth = uniform_mesh ? 0.0 : options.soft_interior_growth;
  o.fine_fin_ray = reference && options.refinement.finger;
  return o;
}

std::vector<LabelsArm> arms_of(const LabelsOptions& options) {
  if (!options.arms.empty()) return options.arms;
  return {{"parallel-jaw", false}, {"fin-ray", false}, {"fin-ray", true}, {"leap", false}};
}

}  // namespace

void check_labels_options(const LabelsOptions& options) {
  if (options.refinement.mesh && !(options.production_models && options.soft_interior_growth > 0)) {
    throw std::invalid_argument(
        "grip bench labels: --refine mesh compares a graded soft mesh with a uniform one; give "
        "--models production and a --tet-growth above 0");
  }
  if (options.refinement.finger && !options.production_models) {
    throw std::invalid_argument(
        "grip bench labels: --refine finger compares the production fin-ray finger with a finer "
        "one; give --models production");
  }
  if (options.seeds < 1 || options.candidates < 1) {
    throw std::invalid_argument("grip bench labels: --seeds and --candidates must be at least 1");
  }
  for (const LabelsArm& arm : arms_of(options)) {
    try {
      plan_robustness(arm_options(options, arm, {}, false));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("grip bench labels: ") + e.what());
    }
  }
}

LabelsResult run_labels(const LabelsOptions& options) {
  check_labels_options(options);
  LabelsResult result;
  result.defaults = options.defaults;
  result.reference = reference_parameters(result.defaults, options.refinement);
  result.refinement = options.refinement;
  result.threads = options.threads > 0 ? options.threads : tbb::this_task_arena::max_concurrency();
  const auto start = std::chrono::steady_clock::now();
  for (const LabelsArm& arm : arms_of(options)) {
    LabelsArmResult run{arm, {}, {}};
    spdlog::info("labels: {} x {} objects at the defaults", arm.gripper,
                 arm.soft ? "soft" : "rigid");
    run.defaults = run_robustness(arm_options(options, arm, result.defaults, false));
    if (!options.refinement.any()) {
      result.arms.push_back(std::move(run));
      continue;
    }
    spdlog::info("labels: {} x {} objects at the reference", arm.gripper,
                 arm.soft ? "soft" : "rigid");
    run.reference = run_robustness(arm_options(options, arm, result.reference, true));
    result.arms.push_back(std::move(run));
  }
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace grip::bench
