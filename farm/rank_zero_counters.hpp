#pragma once
// Counters held in an MPI window on rank 0, that every rank adds to and reads one-sidedly,
// without waiting for rank 0 to answer: the work-unit claims and the live progress.
#include <mpi.h>

#include <cstdint>

namespace grip::farm {

class RankZeroCounters {
 public:
  // Collective over `comm`: `count` counters, every one 0 before any rank touches them; the
  // window stays locked for one-sided access until destruction.
  RankZeroCounters(MPI_Comm comm, std::uint64_t count);
  // Collective, except on a rank unwinding from an exception: it must not wait here for the
  // others. Either every rank unwinds (a failure they agreed on) or the caller aborts them;
  // MPI_Finalize frees the window.
  ~RankZeroCounters();
  RankZeroCounters(const RankZeroCounters&) = delete;
  RankZeroCounters& operator=(const RankZeroCounters&) = delete;

  MPI_Win window() const { return window_; }

 private:
  MPI_Win window_ = MPI_WIN_NULL;
};

}  // namespace grip::farm
