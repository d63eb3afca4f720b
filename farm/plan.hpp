#pragma once
// What a farm run does, known before any trial: the objects prepared, the candidates
// synthesized for every object and gripper, and the dataset's layout with one slot per
// candidate. Candidate ids run object by object, gripper by gripper, in synthesis order.
#include <mpi.h>

#include <vector>

#include "farm/farm_object.hpp"
#include "farm/job.hpp"
#include "farm/live_progress.hpp"
#include "io/dataset_plan.hpp"
#include "src/synth/candidate.hpp"

namespace grip::farm {

struct FarmPlan {
  std::vector<FarmObject> objects;           // the job's objects, in order
  io::DatasetPlan dataset;                   // object and gripper records, candidate slots
  std::vector<synth::Candidate> candidates;  // by candidate id
};

// Collective over `comm`; every rank returns the same plan. Object i is prepared on rank
// i mod size and synthesis of (object i, gripper g) runs on rank (i * grippers + g) mod size,
// each with `threads` threads; the results are broadcast bit for bit. Counts objects prepared
// and candidates synthesized in `progress`; logs what each object yields (spdlog, rank 0).
FarmPlan make_plan(const Job& job, MPI_Comm comm, int threads, LiveProgress& progress);

}  // namespace grip::farm
