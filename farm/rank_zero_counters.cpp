#include "farm/rank_zero_counters.hpp"

#include <exception>

namespace grip::farm {

RankZeroCounters::RankZeroCounters(MPI_Comm comm, std::uint64_t count) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const MPI_Aint bytes = rank == 0 ? static_cast<MPI_Aint>(count * sizeof(std::uint64_t)) : 0;
  std::uint64_t* counters = nullptr;
  MPI_Win_allocate(bytes, sizeof(std::uint64_t), MPI_INFO_NULL, comm, &counters, &window_);
  for (std::uint64_t c = 0; rank == 0 && c < count; ++c) counters[c] = 0;
  MPI_Barrier(comm);  // nothing added before rank 0 has zeroed the counters
  MPI_Win_lock_all(MPI_MODE_NOCHECK, window_);
}

RankZeroCounters::~RankZeroCounters() {
  if (std::uncaught_exceptions() > 0) return;
  MPI_Win_unlock_all(window_);
  MPI_Win_free(&window_);
}

}  // namespace grip::farm
