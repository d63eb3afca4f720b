// A writer process for the kill-and-resume test: under mpirun, creates (or resumes) a synthetic
// dataset and writes its pending candidates in small collective batches, each rank taking
// every other pending id. Each rank first writes its pid to <pid folder>/rank<r>.pid so the
// test can SIGKILL it at any moment.
//   grip_io_writer_driver create|resume DATASET PID_FOLDER CANDIDATES
#include <mpi.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "io/dataset_error.hpp"
#include "io/dataset_writer.hpp"
#include "tests/io/synthetic_dataset.hpp"

namespace {

constexpr std::uint64_t kSeed = 11;
constexpr std::size_t kBatchPerRank = 2;
const char* const kJob = "[job]\nname = \"kill-and-resume\"\n";

int run(const std::string& mode, const std::filesystem::path& dataset,
        const std::filesystem::path& pid_folder, std::uint32_t candidates) {
  int rank = 0;
  int size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  std::ofstream(pid_folder / ("rank" + std::to_string(rank) + ".pid")) << ::getpid() << '\n';

  using namespace grip::io;
  const Provenance provenance = testing::synthetic_provenance(kJob, kSeed);
  DatasetWriter writer = mode == "create"
                             ? DatasetWriter::create(dataset, testing::synthetic_plan(candidates),
                                                     provenance, MPI_COMM_WORLD)
                             : DatasetWriter::resume(dataset, provenance, MPI_COMM_WORLD);
  const std::vector<std::uint64_t> pending = writer.pending();
  const std::size_t per_batch = kBatchPerRank * static_cast<std::size_t>(size);
  for (std::size_t begin = 0; begin < pending.size(); begin += per_batch) {
    std::vector<CandidateResult> mine;
    for (std::size_t i = begin; i < std::min(begin + per_batch, pending.size()); ++i) {
      if (static_cast<int>(i % static_cast<std::size_t>(size)) == rank) {
        mine.push_back(testing::synthetic_result(writer.layout(), pending[i], kSeed));
      }
    }
    writer.write(mine);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int status = 0;
  if (argc != 5 || (std::string(argv[1]) != "create" && std::string(argv[1]) != "resume")) {
    std::fprintf(stderr, "usage: %s create|resume DATASET PID_FOLDER CANDIDATES\n", argv[0]);
    status = 2;
  } else {
    try {
      status = run(argv[1], argv[2], argv[3], static_cast<std::uint32_t>(std::atoi(argv[4])));
    } catch (const grip::io::DatasetError& e) {
      std::fprintf(stderr, "%s\n", e.what());
      status = 1;
    }
  }
  MPI_Finalize();
  return status;
}
