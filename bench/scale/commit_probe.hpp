#pragma once
// What the farm model's claim and commit constants are measured with: run under mpirun, it
// times fetch-and-add claims on rank 0's counter (farm::WorkUnitClaims), the farm's per-unit
// commits (io::DatasetWriter::commit_unit: independent writes, a sync, the journal line) and,
// for the rounds what-if, collective commits of a round, of synthetic rows at two row sizes.
#include <mpi.h>

#include <filesystem>
#include <vector>

namespace grip::bench {

struct CommitSample {
  double bytes = 0;    // committed at once: a round's over all ranks, or one unit's
  double seconds = 0;  // median: of the slowest rank's round commit, or of every unit commit
};

struct ProbeResult {
  int ranks = 0;
  double claim_seconds = 0;                // mean time of one claim while every rank claims at once
  double claim_service = 0;                // wall time of all claims / their number: rank 0's rate
  std::vector<CommitSample> commits;       // collective round commits
  std::vector<CommitSample> unit_commits;  // one rank's work unit, every rank committing at once
  double journal_seconds = 0;              // rank 0: one journal line appended and fsync'd
};

// Collective over `comm`. Writes (then removes) a scratch dataset in `folder`.
ProbeResult probe_commit_costs(MPI_Comm comm, const std::filesystem::path& folder);

// The result as one JSON object in `file`, and back; read throws std::runtime_error naming the
// file when it is not such an object.
void write_probe_json(const std::filesystem::path& file, const ProbeResult& result);
ProbeResult read_probe_json(const std::filesystem::path& file);

}  // namespace grip::bench
