#include "farm/work_unit_claims.hpp"

namespace grip::farm {

WorkUnitClaims::WorkUnitClaims(MPI_Comm comm) : counters_(comm, 1) {}

std::uint64_t WorkUnitClaims::claim() {
  const std::uint64_t one = 1;
  std::uint64_t previous = 0;
  MPI_Fetch_and_op(&one, &previous, MPI_UINT64_T, 0, 0, MPI_SUM, counters_.window());
  MPI_Win_flush(0, counters_.window());
  return previous;
}

void WorkUnitClaims::hand_out_no_more(std::uint64_t units) {
  MPI_Accumulate(&units, 1, MPI_UINT64_T, 0, 0, 1, MPI_UINT64_T, MPI_SUM, counters_.window());
  MPI_Win_flush(0, counters_.window());
}

}  // namespace grip::farm
