#include "farm/live_progress.hpp"

#include <thread>

namespace grip::farm {
namespace {

// How often rank 0 looks at the counters while it waits for the other ranks.
constexpr std::chrono::milliseconds kWaitPoll{20};

}  // namespace

LiveProgress::LiveProgress(MPI_Comm comm, double interval)
    : comm_(comm), counters_(comm, kCounters), line_(interval, ProgressLine::stderr_is_terminal()) {
  MPI_Comm_rank(comm, &rank_);
}

void LiveProgress::start_plan(std::uint64_t objects, std::uint64_t pairs) {
  objects_ = objects;
  pairs_ = pairs;
  phase_start_ = now();
}

void LiveProgress::start_trials(std::uint64_t trials) {
  trials_ = true;
  trial_count_ = trials;
  phase_start_ = now();
}

void LiveProgress::add(Counter counter, std::uint64_t n) {
  if (n == 0) return;
  MPI_Accumulate(&n, 1, MPI_UINT64_T, 0, counter, 1, MPI_UINT64_T, MPI_SUM, counters_.window());
  MPI_Win_flush(0, counters_.window());
}

void LiveProgress::poll() {
  if (rank_ != 0) return;
  const double t = now();
  if (!line_.due(t)) return;
  const std::array<std::uint64_t, kCounters> counts = read();
  line_.show(t, counts[kObjects] + counts[kPairs] + counts[kTrials], text(counts, t));
}

void LiveProgress::wait_for_ranks() {
  MPI_Request request;
  MPI_Ibarrier(comm_, &request);
  if (rank_ != 0) {
    MPI_Wait(&request, MPI_STATUS_IGNORE);
    return;
  }
  for (int done = 0;;) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) return;
    poll();
    std::this_thread::sleep_for(kWaitPoll);
  }
}

void LiveProgress::log_plan() {
  if (rank_ != 0) return;
  const std::array<std::uint64_t, kCounters> counts = read();
  const double t = now();
  line_.log(t, counts[kObjects] + counts[kPairs] + counts[kTrials], text(counts, t));
}

void LiveProgress::log_trials(std::uint64_t done) {
  if (rank_ != 0) return;
  const std::array<std::uint64_t, kCounters> counts = read();
  const double t = now();
  line_.log(t, counts[kObjects] + counts[kPairs] + counts[kTrials],
            trial_progress_text(done, trial_count_, t - phase_start_));
}

std::array<std::uint64_t, LiveProgress::kCounters> LiveProgress::read() {
  std::array<std::uint64_t, kCounters> counts{};
  MPI_Get_accumulate(nullptr, 0, MPI_UINT64_T, counts.data(), kCounters, MPI_UINT64_T, 0, 0,
                     kCounters, MPI_UINT64_T, MPI_NO_OP, counters_.window());
  MPI_Win_flush(0, counters_.window());
  return counts;
}

std::string LiveProgress::text(const std::array<std::uint64_t, kCounters>& counts,
                               double now) const {
  const double seconds = now - phase_start_;
  if (trials_) return trial_progress_text(counts[kTrials], trial_count_, seconds);
  return plan_progress_text(counts[kObjects], objects_, counts[kCandidates], counts[kPairs], pairs_,
                            seconds);
}

double LiveProgress::now() const {
  return std::chrono::duration<double>(Clock::now() - clock_start_).count();
}

}  // namespace grip::farm
