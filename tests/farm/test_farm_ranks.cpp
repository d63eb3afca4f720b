// The same job gives the same dataset, record by record, on 3, 2 and 1 ranks, with 1 or 2
// threads and any work unit size; a second run refuses to overwrite it, and a resume of a
// finished dataset has nothing to do. Runs under mpirun -np 3.
#include <gtest/gtest.h>
#include <mpi.h>

#include "farm/farm.hpp"
#include "io/dataset_error.hpp"
#include "tests/farm/farm_test_job.hpp"
#include "tests/io/io_test_files.hpp"

namespace grip::farm {
namespace {

// run_farm on the first `ranks` ranks of the world; the others wait.
FarmReport run_on(int ranks, const FarmOptions& options) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm comm;
  MPI_Comm_split(MPI_COMM_WORLD, rank < ranks ? 0 : MPI_UNDEFINED, rank, &comm);
  FarmReport report;
  if (comm != MPI_COMM_NULL) {
    report = run_farm(options, comm);
    MPI_Comm_free(&comm);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  return report;
}

TEST(FarmRanks, SameDatasetForAnyRankThreadAndWorkUnitSize) {
  int rank = 0, world = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &world);
  ASSERT_EQ(world, 3);
  const std::filesystem::path dir = io::testing::shared_scratch(MPI_COMM_WORLD, "farm_ranks");
  const std::filesystem::path job = dir / "small.toml";
  if (rank == 0) testing::write_file(job, testing::small_job(2, 3, true));
  MPI_Barrier(MPI_COMM_WORLD);

  FarmOptions options;
  options.job = job;
  struct Run {
    int ranks, threads, work_unit_size;
  };
  const std::vector<Run> runs = {{3, 1, 1}, {2, 1, 2}, {1, 2, 3}, {1, 1, 0}};
  std::vector<std::filesystem::path> datasets;
  for (const Run& run : runs) {
    options.output =
        dir / ("ranks" + std::to_string(run.ranks) + "_threads" + std::to_string(run.threads) +
               "_unit" + std::to_string(run.work_unit_size) + ".h5");
    options.threads = run.threads;
    options.work_unit_size = run.work_unit_size;
    const FarmReport report = run_on(run.ranks, options);
    if (rank < run.ranks) {
      EXPECT_EQ(report.candidates, 9u);
      EXPECT_EQ(report.done, 9u);
      EXPECT_EQ(report.done_before, 0u);
      EXPECT_FALSE(report.interrupted);
    }
    datasets.push_back(options.output);
  }
  if (rank == 0) {
    const io::DatasetReader reader(datasets.front());
    int successes = 0, soft_stress = 0;
    for (const io::CandidateRecord& r : reader.candidates()) {
      EXPECT_NE(r.status, io::Status::kPending);
      successes += r.status == io::Status::kSuccess;
      if (r.status == io::Status::kSuccess) {
        EXPECT_EQ(r.d1, 0.0);
      }
      if (reader.stress(r.id)) ++soft_stress;
    }
    EXPECT_GT(successes, 0);
    EXPECT_EQ(soft_stress, 3);  // the soft capsule's candidates, and only they
    for (std::size_t k = 1; k < datasets.size(); ++k) {
      testing::expect_same_dataset(datasets.front(), datasets[k]);
    }
  }

  // A second run does not overwrite the dataset; it names the file and the fix.
  options.output = datasets.front();
  const std::string before = rank == 0 ? io::testing::file_bytes(datasets.front()) : "";
  try {
    run_on(3, options);
    ADD_FAILURE() << "a second run over an existing dataset was not refused";
  } catch (const io::DatasetError& e) {
    EXPECT_NE(std::string(e.what()).find("--resume"), std::string::npos) << e.what();
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank == 0) {
    EXPECT_EQ(io::testing::file_bytes(datasets.front()), before);
  }

  // Resuming a finished dataset finds nothing to do.
  options.resume = true;
  const FarmReport resumed = run_on(3, options);
  EXPECT_EQ(resumed.done_before, 9u);
  EXPECT_EQ(resumed.done, 0u);
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank == 0) std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace grip::farm
