#include "bench/trial/trial_benchmark.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <exception>
#include <memory>
#include <set>
#include <stdexcept>
#include <utility>

#include "bench/common/cpu_clock.hpp"
#include "bench/robustness/robustness_trials.hpp"
#include "src/synth/candidate.hpp"

namespace grip::bench {
namespace {

std::vector<LabelsArm> arms_of(const TrialBenchOptions& options) {
  if (!options.arms.empty()) return options.arms;
  return {{"parallel-jaw", false},
          {"fin-ray", false},
          {"fin-ray", true},
          {"leap", false},
          {"leap", true}};
}

const std::vector<std::string>& categories_of(const TrialBenchOptions& options) {
  return options.categories.empty() ? kLabelsCategories : options.categories;
}

RobustnessSet set_of(const LabelsArm& arm, const std::string& category, bool production_models) {
  return {arm.gripper, category, arm.soft, 1, 1, production_models};
}

// One category's shape of an arm: its candidates and its scenes, built once for every run.
struct Shape {
  std::uint64_t seed = 0;
  std::vector<synth::Candidate> candidates;
  std::unique_ptr<RobustnessScene> defaults;
  std::unique_ptr<RobustnessScene> reference;  // null without the reference round
};

struct PlannedArm {
  TrialBenchArm plan;
  std::vector<Shape> shapes;          // per category asked for; no candidates: none found
  std::vector<std::size_t> shape_of;  // per candidate of the plan
  bool production_models = true;      // TrialBenchOptions::production_models
};

void fall_short(TrialBenchArm& plan, std::string text) {
  spdlog::warn("{}", text);
  plan.shortfalls.push_back(std::move(text));
}

// The first shape of the set's category that gets a candidate, its `wanted` candidates, its
// object and scenes; no candidates (and a shortfall) if none does or it cannot be prepared.
Shape prepare_shape(const RobustnessSet& set, int wanted, const TrialBenchResult& result,
                    TrialBenchArm& plan) {
  const std::string name = labels_arm_name(plan.arm) + " x " + set.category;
  Shape shape;
  for (std::uint64_t seed = 1; seed <= kSeedsTriedPerShape && shape.candidates.empty(); ++seed) {
    shape.seed = seed;
    shape.candidates = synthesize_candidates(set, seed, wanted);
  }
  if (shape.candidates.empty()) {
    fall_short(plan, name + ": no candidate on seeds 1-" + std::to_string(kSeedsTriedPerShape));
    return shape;
  }
  if (static_cast<int>(shape.candidates.size()) < wanted) {
    fall_short(plan, name + " seed " + std::to_string(shape.seed) + ": " +
                         std::to_string(shape.candidates.size()) + " of " + std::to_string(wanted) +
                         " candidates synthesized");
  }
  try {
    const trial::TrialObject object = make_object(set, shape.seed);
    shape.defaults = std::make_unique<RobustnessScene>(set, object, result.defaults);
    if (result.reference_run) {
      shape.reference = std::make_unique<RobustnessScene>(set, object, result.reference);
    }
  } catch (const std::exception& e) {
    fall_short(plan,
               name + " seed " + std::to_string(shape.seed) + ": no trials (" + e.what() + ")");
    shape.candidates.clear();
  }
  return shape;
}

PlannedArm plan_arm(const LabelsArm& arm, const TrialBenchOptions& options,
                    const TrialBenchResult& result) {
  PlannedArm p;
  p.plan = {arm,
            robustness_gripper_model(arm.gripper, options.production_models),
            robustness_object_model(arm.soft, options.production_models),
            {},
            {}};
  p.production_models = options.production_models;
  const std::vector<std::string>& categories = categories_of(options);
  const int count = options.candidates > 0 ? options.candidates : trial_bench_candidates(arm);
  const int c = static_cast<int>(categories.size());
  for (int j = 0; j < std::min(c, count); ++j) {
    const int wanted = count / c + (j < count % c ? 1 : 0);
    p.shapes.push_back(prepare_shape(set_of(arm, categories[j], options.production_models), wanted,
                                     result, p.plan));
  }
  for (int i = 0; i < count; ++i) {
    const Shape& shape = p.shapes[i % c];
    const auto k = static_cast<std::size_t>(i / c);
    if (k >= shape.candidates.size()) continue;
    p.plan.candidates.push_back({categories[i % c], shape.seed, k});
    p.shape_of.push_back(i % c);
  }
  spdlog::info("trial: {}: {} candidate(s)", labels_arm_name(arm), p.plan.candidates.size());
  return p;
}

// One trial alone on this thread (a batch of one on one thread), timed.
TrialBenchRun run_slot(const TrialBenchSlot& slot, const PlannedArm& arm) {
  const TrialBenchCandidate& c = arm.plan.candidates[slot.candidate];
  const Shape& shape = arm.shapes[arm.shape_of[slot.candidate]];
  const RobustnessScene& scene = slot.reference ? *shape.reference : *shape.defaults;
  const std::vector<synth::Candidate> one = {shape.candidates[c.candidate]};
  const double cpu_start = thread_cpu_seconds();
  const double process_start = process_cpu_seconds();
  const auto start = std::chrono::steady_clock::now();
  const std::vector<trial::TrialOutcome> outcomes = scene.run(one, 1);
  TrialBenchRun run;
  run.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.cpu_seconds = thread_cpu_seconds() - cpu_start;
  run.process_cpu_seconds = process_cpu_seconds() - process_start;
  run.slot = slot;
  run.trial = robustness_trial(set_of(arm.plan.arm, c.category, arm.production_models), c.seed,
                               c.candidate, outcomes.front(), scene.parameters());
  run.displacement = outcomes.front().result.record.displacement;
  run.stages = outcomes.front().stage_seconds;
  run.linear_solves = outcomes.front().linear_solves;
  return run;
}

}  // namespace

int trial_bench_candidates(const LabelsArm& arm) {
  if (arm.soft) return 2;
  if (arm.gripper == "parallel-jaw") return 8;
  if (arm.gripper == "leap") return 4;
  return 2;
}

std::vector<TrialBenchSlot> trial_bench_schedule(const std::vector<std::size_t>& candidates,
                                                 int repeats, bool reference) {
  std::vector<TrialBenchSlot> slots;
  const std::size_t most =
      candidates.empty() ? 0 : *std::max_element(candidates.begin(), candidates.end());
  for (int round = 1; round <= repeats + (reference ? 1 : 0); ++round) {
    const bool is_reference = round > repeats;
    for (std::size_t k = 0; k < most; ++k) {
      for (std::size_t arm = 0; arm < candidates.size(); ++arm) {
        if (k < candidates[arm]) slots.push_back({arm, k, is_reference ? 1 : round, is_reference});
      }
    }
  }
  return slots;
}

void check_trial_bench_options(const TrialBenchOptions& options) {
  if (options.candidates < 0) {
    throw std::invalid_argument("grip bench trial: --candidates must not be negative");
  }
  if (options.repeats < 1) {
    throw std::invalid_argument("grip bench trial: --repeats must be at least 1");
  }
  for (const LabelsArm& arm : arms_of(options)) {
    RobustnessOptions o;
    o.grippers = {arm.gripper};
    o.categories = categories_of(options);
    o.rigid = !arm.soft;
    o.soft = arm.soft;
    try {
      plan_robustness(o);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("grip bench trial: ") + e.what());
    }
  }
}

TrialBenchResult run_trial_bench(const TrialBenchOptions& options) {
  check_trial_bench_options(options);
  TrialBenchResult result;
  result.reference = reference_parameters(result.defaults);
  result.repeats = options.repeats;
  result.reference_run = options.reference;
  const auto start = std::chrono::steady_clock::now();
  std::vector<PlannedArm> arms;
  std::vector<std::size_t> counts;
  for (const LabelsArm& arm : arms_of(options)) {
    arms.push_back(plan_arm(arm, options, result));
    counts.push_back(arms.back().plan.candidates.size());
  }
  // A candidate the gripper cannot take throws every time: it runs no more.
  std::set<std::pair<std::size_t, std::size_t>> dropped;
  for (const TrialBenchSlot& slot :
       trial_bench_schedule(counts, options.repeats, options.reference)) {
    if (dropped.contains({slot.arm, slot.candidate})) continue;
    PlannedArm& arm = arms[slot.arm];
    const TrialBenchCandidate& c = arm.plan.candidates[slot.candidate];
    const std::string name = labels_arm_name(arm.plan.arm) + " x " + c.category + " seed " +
                             std::to_string(c.seed) + " candidate " + std::to_string(c.candidate);
    try {
      result.runs.push_back(run_slot(slot, arm));
    } catch (const std::exception& e) {
      fall_short(arm.plan, name + ": no trial (" + e.what() + ")");
      dropped.insert({slot.arm, slot.candidate});
      continue;
    }
    const TrialBenchRun& run = result.runs.back();
    spdlog::info("trial: {}, {}: {:.2f} s CPU, {:.2f} s wall, {} steps, {} iterations, {}", name,
                 slot.reference ? "reference" : "repeat " + std::to_string(slot.repeat),
                 run.cpu_seconds, run.wall_seconds, run.trial.newton.steps,
                 run.trial.newton.iterations, verdict_of(run.trial));
  }
  for (PlannedArm& arm : arms) result.arms.push_back(std::move(arm.plan));
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace grip::bench
