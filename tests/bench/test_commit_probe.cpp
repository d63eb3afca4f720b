// grip bench scale's probe under mpirun -np 2: claims, work units' commits and rounds' commits
// through the farm's own counter and writer are timed, the two row sizes' payloads are what a
// unit and a round hold, and the scratch dataset is gone afterwards; the JSON form reads back
// the same.
#include <gtest/gtest.h>
#include <mpi.h>

#include <filesystem>

#include "bench/scale/commit_probe.hpp"

namespace grip::bench {
namespace {

TEST(CommitProbe, TimesClaimsAndCommitsOnEveryRank) {
  int rank = 0, ranks = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / "grip_commit_probe_test";
  const ProbeResult result = probe_commit_costs(MPI_COMM_WORLD, folder);
  EXPECT_EQ(result.ranks, ranks);
  EXPECT_GT(result.claim_seconds, 0.0);
  EXPECT_GT(result.claim_service, 0.0);
  ASSERT_EQ(result.commits.size(), 2u);
  EXPECT_GT(result.commits[0].seconds, 0.0);
  // 16 rows per rank; trajectory rows are hundreds of times the table's.
  EXPECT_GT(result.commits[1].bytes, 100 * result.commits[0].bytes);
  EXPECT_GT(result.commits[0].bytes, 16.0 * ranks * 100);
  ASSERT_EQ(result.unit_commits.size(), 2u);
  EXPECT_GT(result.unit_commits[0].seconds, 0.0);
  EXPECT_DOUBLE_EQ(result.unit_commits[1].bytes * 4 * ranks, result.commits[1].bytes);
  EXPECT_GT(result.journal_seconds, 0.0);
  MPI_Barrier(MPI_COMM_WORLD);
  EXPECT_FALSE(std::filesystem::exists(folder / ("probe_" + std::to_string(ranks) + ".h5")));

  if (rank == 0) {
    const std::filesystem::path json = folder / "probe.json";
    write_probe_json(json, result);
    const ProbeResult back = read_probe_json(json);
    EXPECT_EQ(back.ranks, result.ranks);
    EXPECT_DOUBLE_EQ(back.commits[1].bytes, result.commits[1].bytes);
    EXPECT_DOUBLE_EQ(back.unit_commits[0].seconds, result.unit_commits[0].seconds);
    EXPECT_DOUBLE_EQ(back.journal_seconds, result.journal_seconds);
    std::filesystem::remove_all(folder);
  }
}

}  // namespace
}  // namespace grip::bench
