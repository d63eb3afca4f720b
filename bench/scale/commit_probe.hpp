#pragma once
// What the farm model's claim and commit constants are measured with: run under mpirun, it
// times fetch-and-add claims on rank 0's counter (farm::WorkUnitClaims) and collective commits
// of synthetic rows through io::DatasetWriter, the farm's own writer, at two row sizes.
#include <mpi.h>

#include <filesystem>
#include <vector>

namespace grip::bench {

struct CommitSample {
  double bytes = 0;    // committed in the round, over all ranks (rows' payload, approximate)
  double seconds = 0;  // median over the rounds of the slowest rank's commit
};

struct ProbeResult {
  int ranks = 0;
  double claim_seconds = 0;  // mean time of one claim while every rank claims at once
  double claim_service = 0;  // wall time of all claims / their number: rank 0's rate
  std::vector<CommitSample> commits;
};

// Collective over `comm`. Writes (then removes) a scratch dataset in `folder`.
ProbeResult probe_commit_costs(MPI_Comm comm, const std::filesystem::path& folder);

// The result as one JSON object in `file`, and back; read throws std::runtime_error naming the
// file when it is not such an object.
void write_probe_json(const std::filesystem::path& file, const ProbeResult& result);
ProbeResult read_probe_json(const std::filesystem::path& file);

}  // namespace grip::bench
