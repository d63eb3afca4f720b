#pragma once
// A deterministic discrete-event model of `grip farm`'s protocol (farm/farm.cpp, docs/farm.md):
// planning shared round-robin and broadcast, work units claimed from rank 0's counter in
// rounds, every round ended by one collective commit with its journal line. It predicts a run's
// wall time from measured costs at rank counts this machine cannot run.
#include <cstdint>
#include <vector>

namespace grip::bench {

// One round's commit (DatasetWriter::write, the progress barrier, the farm's allreduces):
// latency + per_log2 * log2(P) + bytes / bandwidth.
struct CommitModel {
  double latency = 0;    // s: flushes, the journal's fsync
  double per_log2 = 0;   // s per log2(ranks): the collectives' tree depth
  double bandwidth = 0;  // bytes/s into the file; 0: unlimited
  double seconds(int ranks, double bytes) const;
};

// A claim: one MPI fetch-and-add on rank 0's counter. Claims queue at rank 0, each holding the
// counter for `service` seconds; the round trip adds `latency`.
struct ClaimModel {
  double latency = 0;  // s
  double service = 0;  // s
};

struct FarmCosts {
  double startup = 0;              // s: mpirun, MPI_Init, the job read, the dataset created/closed
  double prepare_rigid = 0;        // s to prepare a rigid object (repair, scale)
  double prepare_soft = 0;         // s to prepare a soft object (tetrahedralization too)
  double synthesis = 0;            // s per candidate synthesized
  double broadcast_per_log2 = 0;   // s per broadcast (one per object and per pair) per log2(ranks)
  double scene_build = 0;          // s to build a trial scene not among a rank's last two
  double bytes_per_candidate = 0;  // committed bytes per result row
  ClaimModel claim;
  CommitModel commit;
};

// The order work units are handed out in: the farm's (candidate ids), or, as a what-if, the
// units of the costliest kind first (the estimated cost known before the run: the mean of the
// unit's class).
enum class UnitOrder { kIds, kHeaviestFirst };

// A job as the model sees it: candidates in id order (object by object, gripper by gripper),
// each with its trial cost, its (object, gripper) pair and that pair's class (e.g. "fin-ray x
// soft"); objects with their kind.
struct ModelJob {
  std::vector<bool> object_soft;  // by object
  std::uint32_t grippers = 1;
  std::vector<double> candidate_seconds;      // by candidate id: wall seconds of its trial
  std::vector<std::uint32_t> candidate_pair;  // object * grippers + gripper
  std::vector<double> class_mean;             // by pair: the mean cost of its class (for ordering)
  int work_unit_size = 4;                     // candidates per work unit (--batch)
  int round_work_units = 4;  // work units per rank per round ([farm] round_batches)
};

struct ModelOptions {
  UnitOrder order = UnitOrder::kIds;
  // What-if: no barrier at a round's end; each rank commits its own rows after each unit
  // independently and runs on: a write takes latency + bytes / bandwidth, no log2 term, and
  // the file takes one write's bytes at a time (the bandwidth is shared).
  bool barrier_free = false;
};

struct ModelRun {
  int ranks = 0;
  std::uint64_t units = 0;
  std::uint64_t rounds = 0;
  double startup = 0;      // s
  double plan = 0;         // s, planning (prepare, synthesize, broadcasts)
  double trial_phase = 0;  // s, from the first claim to the last commit
  double total = 0;        // s, time to solution
  // Rank-seconds of the trial phase, summed over ranks: trials (scene builds included),
  // claims (waiting on rank 0's counter), idle at round ends, commits.
  double work = 0;
  double claiming = 0;
  double idle = 0;
  double committing = 0;
};

// The model's run of `job` on `ranks` ranks (one core each). Deterministic.
ModelRun simulate_farm(const ModelJob& job, const FarmCosts& costs, int ranks,
                       const ModelOptions& options = {});

}  // namespace grip::bench
