#include "solver/batch/parallel_engine.hpp"

#include <tbb/task_arena.h>

#include <algorithm>
#include <utility>

namespace grip::solver {

ParallelEngine::ParallelEngine(int threads)
    : threads_(threads > 0 ? threads : tbb::this_task_arena::max_concurrency()) {}

ParallelEngine::~ParallelEngine() = default;

int ParallelEngine::add(std::shared_ptr<const Model> model) {
  models_.push_back(model);
  return HostEnvironments::add(std::move(model));
}

BatchStepReport ParallelEngine::step() {
  BatchStepReport report;
  std::vector<int> stepping;
  for (int i = 0; i < size(); ++i) {
    if (!active(i)) continue;
    ++report.stepped;
    // The CPU engine checks a start in its first step; the batch assumes it is free.
    if (environment(i).time() == 0.0 && !environment(i).check_start()) {
      ++report.failed;
      continue;
    }
    stepping.push_back(i);
  }
  if (stepping.empty()) return report;
  if (stepping != members_ || !batch_) {
    std::vector<std::shared_ptr<const Model>> models;
    for (int i : stepping) models.push_back(models_[static_cast<std::size_t>(i)]);
    batch_ = std::make_unique<ParallelBatch>(std::move(models), threads_);
    members_ = stepping;
  }
  std::vector<State> states;
  for (int i : stepping) states.push_back(environment(i).state());
  std::vector<ParallelStepResult> results =
      batch_->step(states, std::vector<unsigned char>(stepping.size(), 1), policy_);
  for (std::size_t k = 0; k < stepping.size(); ++k) {
    ParallelStepResult& r = results[k];
    report.iterations += r.diagnostics.newton_iterations;
    if (r.failure != Failure::kNone) ++report.failed;
    environment(stepping[k])
        .adopt_step({std::move(states[k]), std::move(r.diagnostics), r.failure,
                     std::move(r.message), std::move(r.start_positions), r.h, r.kappa,
                     std::move(r.friction), r.cg_iterations});
  }
  report.rounds = batch_->rounds();
  report.frozen = static_cast<long>(report.rounds) * report.stepped - report.iterations;
  return report;
}

}  // namespace grip::solver
