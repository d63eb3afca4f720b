#pragma once
// Where ranks ask for their next work unit: a counter per queue held in an MPI window on rank 0
// and taken with a one-sided atomic fetch-and-add. A rank that finishes a work unit takes the
// next one at once, without waiting for any other rank (rank 0 included) to answer, so fast
// ranks run more work units than slow ones. The farm keeps two queues when it has PETSc groups:
// the units every rank may run, and those only a group's leader may (farm/petsc_groups.hpp).
#include <mpi.h>

#include <cstdint>

#include "farm/rank_zero_counters.hpp"

namespace grip::farm {

class WorkUnitClaims {
 public:
  // Collective over `comm`: `queues` counters, each starting at 0. Destruction is collective as
  // RankZeroCounters' is.
  explicit WorkUnitClaims(MPI_Comm comm, int queues = 1);

  // The queue's counter before this rank's increment: 0, 1, 2, ... over all ranks, each value
  // handed out once.
  std::uint64_t claim(int queue = 0);
  // Any rank: every later claim of any queue gets at least `units`, so every rank stops after
  // the work unit it is running (a stop request or a failed trial on one rank ends all of them).
  void hand_out_no_more(std::uint64_t units);

 private:
  RankZeroCounters counters_;
  int queues_ = 1;
};

}  // namespace grip::farm
