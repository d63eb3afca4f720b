#include "solver/batch/batch.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>

namespace grip::solver {

namespace {

int resolve_threads(int threads) {
  return threads > 0 ? threads : tbb::this_task_arena::max_concurrency();
}

}  // namespace

Batch::Batch(int threads) : threads_(resolve_threads(threads)), arena_(threads_) {}

int Batch::add(std::shared_ptr<const Model> model) {
  const int index = HostEnvironments::add(std::move(model));
  environment(index).set_policy(policy_);
  return index;
}

void Batch::set_policy(const StepPolicy& policy) {
  policy_ = policy;
  for (int i = 0; i < size(); ++i) environment(i).set_policy(policy);
}

BatchStepReport Batch::step() {
  BatchStepReport report;
  std::vector<int> iterating;
  for (int i = 0; i < size(); ++i) {
    if (active(i)) iterating.push_back(i);
  }
  report.stepped = static_cast<int>(iterating.size());
  std::vector<Environment::Progress> progress(static_cast<std::size_t>(size()));

  // Runs `work` on every environment in `iterating`, one task per environment so that the
  // threads balance environments of different sizes.
  auto for_each_iterating = [&](auto&& work) {
    arena_.execute([&] {
      tbb::parallel_for(
          tbb::blocked_range<std::size_t>(0, iterating.size(), 1),
          [&](const tbb::blocked_range<std::size_t>& range) {
            for (std::size_t k = range.begin(); k < range.end(); ++k) work(iterating[k]);
          },
          tbb::simple_partitioner());
    });
  };

  for_each_iterating([&](int i) { progress[i] = environment(i).begin_step(); });
  for (;;) {
    // Drop environments that finished their step (frozen until the next one) or failed.
    // Converged ones are held only without freezing, until all have converged.
    std::erase_if(iterating, [&](int i) {
      if (progress[i] == Environment::Progress::kFailed) ++report.failed;
      return progress[i] != Environment::Progress::kIterating &&
             progress[i] != Environment::Progress::kConverged;
    });
    if (iterating.empty()) break;
    if (std::all_of(iterating.begin(), iterating.end(),
                    [&](int i) { return progress[i] == Environment::Progress::kConverged; })) {
      for_each_iterating([&](int i) { progress[i] = environment(i).finish_held_step(); });
      break;
    }
    ++report.rounds;
    report.iterations += static_cast<long>(iterating.size());
    report.frozen += static_cast<long>(report.stepped - static_cast<int>(iterating.size()));
    for_each_iterating([&](int i) { progress[i] = environment(i).iterate(); });
  }
  return report;
}

}  // namespace grip::solver
