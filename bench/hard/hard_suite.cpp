#include "bench/hard/hard_suite.hpp"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <limits>
#include <stdexcept>

#include "src/scene/invariants.hpp"

namespace grip::bench {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

InvariantCheck check_invariants(const solver::Environment& env) {
  return {scene::count_intersections(env), env.min_volume_ratio()};
}

double HardCaseResult::newton_mean() const {
  if (steps.empty()) return 0.0;
  long total = 0;
  for (const HardStep& s : steps) total += s.newton_iterations;
  return static_cast<double>(total) / static_cast<double>(steps.size());
}

int HardCaseResult::newton_max() const {
  int most = 0;
  for (const HardStep& s : steps) most = std::max(most, s.newton_iterations);
  return most;
}

long HardCaseResult::line_search_total() const {
  long total = 0;
  for (const HardStep& s : steps) total += s.line_search_steps;
  return total;
}

double HardCaseResult::min_distance_over_d_hat() const {
  double least = std::numeric_limits<double>::infinity();
  for (const HardStep& s : steps) least = std::min(least, s.min_distance);
  return least / d_hat;
}

double HardCaseResult::min_volume_ratio() const {
  double least = 1.0;
  for (const HardStep& s : steps) least = std::min(least, s.min_volume_ratio);
  return least;
}

HardCaseResult run_hard_case(const HardCase& hard_case) {
  HardCaseResult result;
  result.name = hard_case.name;
  result.challenge = hard_case.challenge;
  result.d_hat = hard_case.scene.sim.d_hat;
  result.planned_steps = hard_case.steps;
  result.failure_expected = hard_case.failure_expected;
  std::shared_ptr<const solver::Model> model;
  try {
    model = solver::Model::build(hard_case.scene);
  } catch (const std::invalid_argument& e) {
    result.solver_failure = std::string("scene rejected: ") + e.what();
    return result;
  }
  solver::Environment env(model);
  for (int s = 0; s < hard_case.steps; ++s) {
    const Clock::time_point step_start = Clock::now();
    const bool accepted = env.step();
    result.solve_seconds += seconds_since(step_start);
    if (!accepted) {
      result.solver_failure = env.failure();
      break;
    }
    const Clock::time_point check_start = Clock::now();
    const solver::StepDiagnostics& d = env.last_step();
    result.steps.push_back(
        {d.newton_iterations, d.line_search_steps, d.min_distance, d.min_volume_ratio});
    const InvariantCheck invariants = check_invariants(env);
    if (invariants.intersections != 0) ++result.intersecting_steps;
    if (!(invariants.min_volume_ratio > 0.0)) ++result.inverted_steps;
    if (hard_case.check && result.physical_failure.empty()) {
      const std::string broken = hard_case.check(env, s + 1 == hard_case.steps);
      if (!broken.empty())
        result.physical_failure = "step " + std::to_string(s + 1) + ": " + broken;
    }
    result.check_seconds += seconds_since(check_start);
  }
  return result;
}

std::vector<HardCaseResult> run_hard_cases(const std::vector<HardCase>& cases, int threads) {
  std::vector<HardCaseResult> results(cases.size());
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, cases.size(), 1),
        [&](const tbb::blocked_range<std::size_t>& range) {
          for (std::size_t i = range.begin(); i != range.end(); ++i) {
            results[i] = run_hard_case(cases[i]);
          }
        },
        tbb::simple_partitioner());
  });
  return results;
}

}  // namespace grip::bench
