#include "farm/work_unit_claims.hpp"

#include <exception>
#include <stdexcept>

namespace grip::farm {

WorkUnitClaims::WorkUnitClaims(MPI_Comm comm, std::uint64_t rounds) : rounds_(rounds) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const MPI_Aint bytes = rank == 0 ? static_cast<MPI_Aint>(rounds * sizeof(std::uint64_t)) : 0;
  std::uint64_t* counters = nullptr;
  MPI_Win_allocate(bytes, sizeof(std::uint64_t), MPI_INFO_NULL, comm, &counters, &window_);
  for (std::uint64_t r = 0; rank == 0 && r < rounds; ++r) counters[r] = 0;
  MPI_Barrier(comm);  // no claim before rank 0 has zeroed the counters
  MPI_Win_lock_all(MPI_MODE_NOCHECK, window_);
}

WorkUnitClaims::~WorkUnitClaims() {
  if (std::uncaught_exceptions() > 0) return;
  MPI_Win_unlock_all(window_);
  MPI_Win_free(&window_);
}

std::uint64_t WorkUnitClaims::claim(std::uint64_t round) {
  if (round >= rounds_) throw std::out_of_range("WorkUnitClaims: no such round");
  const std::uint64_t one = 1;
  std::uint64_t previous = 0;
  MPI_Fetch_and_op(&one, &previous, MPI_UINT64_T, 0, static_cast<MPI_Aint>(round), MPI_SUM,
                   window_);
  MPI_Win_flush(0, window_);
  return previous;
}

}  // namespace grip::farm
