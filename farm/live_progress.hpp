#pragma once
// A farm run's progress while it runs, from every rank: objects prepared and candidates
// synthesized while planning, then trials ended. Each rank adds what it finishes to counters on
// rank 0 by one-sided MPI accumulates and goes on, waiting for nobody; rank 0 reads them and
// shows its progress line whenever it polls: after every solver step of its own trials, and
// while it waits for the other ranks.
#include <mpi.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <string>

#include "farm/progress_line.hpp"
#include "farm/rank_zero_counters.hpp"

namespace grip::farm {

class LiveProgress {
 public:
  enum Counter : int { kObjects, kPairs, kCandidates, kTrials, kCounters };

  // Collective over `comm`: every counter starts at 0. interval: ProgressLine's (< 0: default).
  // Destruction is collective as RankZeroCounters' is.
  LiveProgress(MPI_Comm comm, double interval);

  // Every rank: what there is to do, and its clock started.
  void start_plan(std::uint64_t objects, std::uint64_t pairs);
  void start_trials(std::uint64_t trials);

  void add(Counter counter, std::uint64_t n = 1);  // any rank; returns at once
  void poll();  // rank 0: shows the line if due; other ranks: nothing

  // Collective: returns once every rank has called it, rank 0 polling meanwhile. Called where
  // the ranks would wait for each other anyway (before a broadcast of everyone's results), so it
  // changes nothing of who does what.
  void wait_for_ranks();

  // Rank 0: a log line now, whatever the interval: planning's totals; trials `done`.
  void log_plan();
  void log_trials(std::uint64_t done);

 private:
  using Clock = std::chrono::steady_clock;
  std::array<std::uint64_t, kCounters> read();
  std::string text(const std::array<std::uint64_t, kCounters>& counts, double now) const;
  double now() const;

  MPI_Comm comm_;
  int rank_ = 0;
  RankZeroCounters counters_;
  ProgressLine line_;
  Clock::time_point clock_start_ = Clock::now();
  bool trials_ = false;                                      // planning is over
  double phase_start_ = 0;                                   // s on now()'s clock
  std::uint64_t objects_ = 0, pairs_ = 0, trial_count_ = 0;  // to do
};

}  // namespace grip::farm
