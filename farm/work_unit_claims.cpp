#include "farm/work_unit_claims.hpp"

#include <stdexcept>

namespace grip::farm {

WorkUnitClaims::WorkUnitClaims(MPI_Comm comm, std::uint64_t rounds)
    : counters_(comm, rounds), rounds_(rounds) {}

std::uint64_t WorkUnitClaims::claim(std::uint64_t round) {
  if (round >= rounds_) throw std::out_of_range("WorkUnitClaims: no such round");
  const std::uint64_t one = 1;
  std::uint64_t previous = 0;
  MPI_Fetch_and_op(&one, &previous, MPI_UINT64_T, 0, static_cast<MPI_Aint>(round), MPI_SUM,
                   counters_.window());
  MPI_Win_flush(0, counters_.window());
  return previous;
}

}  // namespace grip::farm
