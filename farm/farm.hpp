#pragma once
// `grip farm JOB.toml`: plan the job (objects prepared and candidates synthesized in parallel
// across ranks), create or resume its dataset, then run every pending candidate's trial in
// work units that ranks claim as they go, each rank committing each of its units as it ends,
// without waiting for the others. One process with threads, or many MPI ranks: the same
// dataset (docs/farm.md).
#include <mpi.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>

namespace grip::farm {

struct FarmOptions {
  std::filesystem::path job;      // the job file
  std::filesystem::path output;   // the dataset; empty: the job's [job] output
  bool resume = false;            // continue an existing dataset of the same job
  int threads = 0;                // per rank; 0: this node's cores shared by its ranks
  int work_unit_size = 0;         // candidates per work unit; 0: the job's, else 4 per thread
  double progress_interval = -1;  // s between progress lines; < 0: 1 on a terminal, else 5
  std::string grip_version;       // recorded in the dataset's provenance
  std::string git_revision;
  // Rank 0 calls it on the dataset to resume before anything opens it; it throws
  // io::DatasetError for a file HDF5 cannot read (grip's: app/dataset_probe.hpp).
  std::function<void(const std::filesystem::path&)> check_dataset;
  // PETSc's options for the job's PETSc groups (grip farm JOB -- OPTIONS), e.g. -ksp_rtol 1e-12.
  std::vector<std::string> petsc_options;
};

struct FarmReport {
  std::filesystem::path dataset;
  int ranks = 1;
  int threads = 1;                 // per rank
  int work_unit_size = 1;          // candidates per work unit
  std::uint64_t candidates = 0;    // in the dataset
  std::uint64_t done_before = 0;   // already committed when the run started (resume)
  std::uint64_t done = 0;          // committed by this run
  double plan_seconds = 0;         // preparing objects and synthesizing candidates
  double trial_seconds = 0;        // running and committing trials
  bool interrupted = false;        // stopped by SIGINT or SIGTERM before the end
  int petsc_groups = 0;            // [farm] PETSc groups of the run
  std::uint64_t petsc_solves = 0;  // Newton systems the groups solved
};

// A trial that failed on some rank (an exception of the solver, e.g. CHOLMOD out of memory),
// thrown on every rank alike once every rank's work units in flight are committed.
class TrialError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Collective over `comm`. Throws config::ConfigError for a bad job file, io::DatasetError for
// a dataset that exists without --resume (or is missing, or from another job, with it), on
// every rank alike; nothing already written is touched. Throws TrialError, on every rank alike,
// when a trial failed on any rank: the results committed until then are kept.
FarmReport run_farm(const FarmOptions& options, MPI_Comm comm);

}  // namespace grip::farm
