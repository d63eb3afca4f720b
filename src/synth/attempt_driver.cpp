#include "src/synth/attempt_driver.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include <tbb/parallel_for.h>

namespace grip::synth {

SynthesisResult run_attempts(int count, std::int64_t max_attempts, int block,
                             const std::function<AttemptOutcome(std::int64_t)>& attempt) {
  if (count < 0 || block < 1) throw std::invalid_argument("run_attempts: bad count or block size");
  const auto start = std::chrono::steady_clock::now();
  SynthesisResult result;
  std::vector<AttemptOutcome> outcomes;
  while (static_cast<int>(result.candidates.size()) < count && result.attempts < max_attempts) {
    const std::int64_t first = result.attempts;
    // Near the end a block shrinks to twice the candidates still missing (at least 8): fewer
    // wasted attempts, and the sizes still depend on nothing but the outcomes so far.
    const std::int64_t missing = count - static_cast<std::int64_t>(result.candidates.size());
    const std::int64_t size = std::min<std::int64_t>(
        {block, std::max<std::int64_t>(2 * missing, 8), max_attempts - first});
    outcomes.assign(static_cast<std::size_t>(size), {});
    tbb::parallel_for(std::int64_t{0}, size, [&](std::int64_t i) {
      outcomes[static_cast<std::size_t>(i)] = attempt(first + i);
    });
    for (AttemptOutcome& outcome : outcomes) {
      if (outcome.candidate) {
        ++result.accepted;
        if (static_cast<int>(result.candidates.size()) < count) {
          result.candidates.push_back(std::move(*outcome.candidate));
        }
      } else {
        ++result.rejections[outcome.rejection];
      }
    }
    result.attempts += size;
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace grip::synth
