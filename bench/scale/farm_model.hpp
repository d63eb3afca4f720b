#pragma once
// A deterministic discrete-event model of `grip farm`'s protocol (farm/farm.cpp, docs/farm.md):
// planning shared round-robin and broadcast, work units claimed from rank 0's counter, each
// committed by its rank as it ends (independent writes sharing the file, rank 0 appending the
// journal lines); or, as a what-if, the former rounds, each ended by one collective commit. It
// predicts a run's wall time from measured costs at rank counts this machine cannot run.
#include <cstdint>
#include <vector>

namespace grip::bench {

// A commit: latency + per_log2 * log2(P) + bytes / bandwidth. A round's (DatasetWriter::write,
// the progress barrier, the farm's allreduces), or one unit's (DatasetWriter::commit_unit: no
// collective, so no log2 term).
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
  CommitModel commit;       // a round's collective commit (the rounds what-if)
  CommitModel unit_commit;  // one work unit's independent commit, on its rank
  double journal_line = 0;  // s of rank 0's time per journal line (the units that arrived)
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
  int round_work_units = 4;                   // work units per rank per round (rounds what-if)
};

struct ModelOptions {
  UnitOrder order = UnitOrder::kIds;
  // What-if, the farm before per-unit commits: units handed out in rounds of round_work_units
  // per rank, every round ended by one collective commit that every rank waits for. Without
  // it (the farm): each rank commits each unit as it ends and claims on; the file takes one
  // write's bytes at a time (the bandwidth is shared) and rank 0 pays the journal's lines.
  bool rounds = false;
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
  // claims (waiting on rank 0's counter), idle (at round ends, or after the last unit),
  // commits (rank 0's journal lines included).
  double work = 0;
  double claiming = 0;
  double idle = 0;
  double committing = 0;
};

// The model's run of `job` on `ranks` ranks (one core each). Deterministic.
ModelRun simulate_farm(const ModelJob& job, const FarmCosts& costs, int ranks,
                       const ModelOptions& options = {});

}  // namespace grip::bench
