#include "farm/work_unit_claims.hpp"

namespace grip::farm {

WorkUnitClaims::WorkUnitClaims(MPI_Comm comm, int queues)
    : counters_(comm, static_cast<std::uint64_t>(queues)), queues_(queues) {}

std::uint64_t WorkUnitClaims::claim(int queue) {
  const std::uint64_t one = 1;
  std::uint64_t previous = 0;
  MPI_Fetch_and_op(&one, &previous, MPI_UINT64_T, 0, queue, MPI_SUM, counters_.window());
  MPI_Win_flush(0, counters_.window());
  return previous;
}

void WorkUnitClaims::hand_out_no_more(std::uint64_t units) {
  for (int queue = 0; queue < queues_; ++queue) {
    MPI_Accumulate(&units, 1, MPI_UINT64_T, 0, queue, 1, MPI_UINT64_T, MPI_SUM, counters_.window());
  }
  MPI_Win_flush(0, counters_.window());
}

}  // namespace grip::farm
