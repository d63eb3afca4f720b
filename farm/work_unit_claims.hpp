#pragma once
// Where ranks ask for their next work unit: one counter per commit round, held in an MPI window
// on rank 0 and taken with a one-sided atomic fetch-and-add. A rank that finishes a work unit
// takes the next one at once, without waiting for any other rank (rank 0 included) to answer,
// so fast ranks run more work units than slow ones.
#include <mpi.h>

#include <cstdint>

#include "farm/rank_zero_counters.hpp"

namespace grip::farm {

class WorkUnitClaims {
 public:
  // Collective over `comm`: every counter starts at 0. Destruction is collective as
  // RankZeroCounters' is.
  WorkUnitClaims(MPI_Comm comm, std::uint64_t rounds);

  // The round's counter before this rank's increment: 0, 1, 2, ... over all ranks, each value
  // handed out once.
  std::uint64_t claim(std::uint64_t round);

 private:
  RankZeroCounters counters_;
  std::uint64_t rounds_ = 0;
};

}  // namespace grip::farm
