#pragma once
// Runs numbered synthesis attempts in parallel blocks until enough succeed, and keeps the
// first `count` successes in attempt order: the result does not depend on the thread count.
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "src/synth/candidate.hpp"

namespace grip::synth {

struct AttemptOutcome {
  std::optional<Candidate> candidate;  // empty: rejected
  std::string rejection;               // why, when rejected (a short key for the statistics)
};

struct SynthesisResult {
  std::vector<Candidate> candidates;               // at most `count`, in attempt order
  std::int64_t attempts = 0;                       // attempts evaluated
  std::int64_t accepted = 0;                       // of which succeeded (may exceed count)
  std::map<std::string, std::int64_t> rejections;  // attempts rejected, by reason
  double seconds = 0.0;                            // wall time

  double accepted_fraction() const { return attempts ? double(accepted) / double(attempts) : 0.0; }
};

// Evaluates attempts 0, 1, 2, ... in blocks of at most `block` (each in parallel with TBB) until
// `count` have succeeded or `max_attempts` were made. `attempt` must be thread-safe and
// depend only on its index.
SynthesisResult run_attempts(int count, std::int64_t max_attempts, int block,
                             const std::function<AttemptOutcome(std::int64_t)>& attempt);

}  // namespace grip::synth
