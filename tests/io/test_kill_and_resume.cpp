// SIGKILL a writer rank at seeded random moments, resume, and compare with an uninterrupted
// run: every record present once, equal to the reference, and the files byte-identical. The
// writer runs as a separate program under mpirun (two ranks); the test is its supervisor.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "io/dataset_reader.hpp"
#include "io/journal.hpp"
#include "tests/io/io_test_files.hpp"

namespace grip::io {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

constexpr int kCandidates = 24;  // 6 batches of 2 candidates per rank

// Starts `mpiexec -np <ranks> driver <mode> <dataset> <folder> <candidates>` in its own
// process group, its output going to <folder>/<log>.
pid_t start_driver(int ranks, const std::string& mode, const fs::path& dataset,
                   const fs::path& folder, const std::string& log) {
  std::fflush(nullptr);  // or the child inherits and repeats unwritten output
  const pid_t pid = ::fork();
  if (pid != 0) return pid;
  ::setpgid(0, 0);
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
  const std::string output = (folder / log).string();
  std::freopen(output.c_str(), "w", stdout);
  std::freopen(output.c_str(), "a", stderr);
  const std::string np = std::to_string(ranks);
  const std::string count = std::to_string(kCandidates);
  const std::string dataset_name = dataset.string();
  const std::string folder_name = folder.string();
  ::execl(GRIP_MPIEXEC, GRIP_MPIEXEC, "-np", np.c_str(), "--oversubscribe", GRIP_WRITER_DRIVER,
          mode.c_str(), dataset_name.c_str(), folder_name.c_str(), count.c_str(),
          static_cast<char*>(nullptr));
  std::_Exit(127);
}

// Waits for the driver; kills its process group if it takes longer than a minute.
int wait_driver(pid_t pid) {
  const auto deadline = std::chrono::steady_clock::now() + 60s;
  int status = 0;
  while (::waitpid(pid, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(-pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      ADD_FAILURE() << "the writer driver hung and was killed";
      return -1;
    }
    std::this_thread::sleep_for(2ms);
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// Complete "done" lines in the journal so far.
int committed_batches(const fs::path& journal) {
  std::ifstream in(journal);
  int lines = 0;
  for (std::string line; std::getline(in, line);) lines += line.rfind("done ", 0) == 0;
  return lines;
}

pid_t read_pid(const fs::path& file) {
  pid_t pid = 0;
  std::ifstream(file) >> pid;
  return pid;
}

std::string log_text(const fs::path& file) { return testing::file_bytes(file); }

// Where a kill landed, from what it left behind: committed batches, and candidates whose
// rows or done flags were written but whose batch never reached the journal.
std::string describe_interruption(const fs::path& dataset) {
  const Journal::Contents journal = Journal::read(Journal::path_for(dataset));
  const std::set<std::uint64_t> journaled(journal.done.begin(), journal.done.end());
  const DatasetReader reader(dataset);
  const std::vector<std::uint8_t> done = reader.done();
  const std::vector<CandidateRecord> records = reader.candidates();
  int flagged = 0;
  int rows_only = 0;
  for (std::uint64_t id = 0; id < done.size(); ++id) {
    if (journaled.count(id)) continue;
    flagged += done[id] != 0;
    rows_only += done[id] == 0 && records[id].status != Status::kPending;
  }
  std::ostringstream out;
  out << journaled.size() << " candidates journaled, " << flagged << " flagged but not journaled, "
      << rows_only << " with rows but no flag";
  return out.str();
}

// One killed run and its resume, for each seed. The seed picks how many batches to let
// through, then a fraction of the last batch's duration to wait (so the kill lands anywhere
// in the next batch: writing rows, flags or the journal line) and which rank dies.
void kill_and_resume(std::uint64_t seed, const fs::path& folder, const fs::path& reference) {
  std::mt19937_64 random(seed);
  const int after_batches = 2 + static_cast<int>(random() % 3);
  const double fraction = static_cast<double>(random() % 1000) / 1000.0;
  const int victim = static_cast<int>(random() % 2);
  const fs::path run = folder / ("seed" + std::to_string(seed));
  fs::create_directories(run);
  const fs::path dataset = run / "data.h5";
  const fs::path journal = Journal::path_for(dataset);
  const pid_t driver = start_driver(2, "create", dataset, run, "log");
  auto previous = std::chrono::steady_clock::now();
  auto last = previous;
  for (int seen = 0; seen < after_batches;) {
    int status = 0;
    ASSERT_EQ(::waitpid(driver, &status, WNOHANG), 0)
        << "the writer ended before the kill point: " << log_text(run / "log");
    const int now_seen = committed_batches(journal);
    if (now_seen > seen) {
      previous = last;
      last = std::chrono::steady_clock::now();
      seen = now_seen;
    }
    std::this_thread::sleep_for(100us);
  }
  const auto delay =
      std::chrono::duration_cast<std::chrono::microseconds>(fraction * (last - previous));
  std::this_thread::sleep_for(delay);
  ASSERT_EQ(::kill(read_pid(run / ("rank" + std::to_string(victim) + ".pid")), SIGKILL), 0);
  ASSERT_NE(wait_driver(driver), 0) << "the writer finished before it was killed";
  std::printf("seed %llu: killed rank %d after %d batches + %lld us: %s\n",
              static_cast<unsigned long long>(seed), victim, after_batches,
              static_cast<long long>(delay.count()), describe_interruption(dataset).c_str());

  ASSERT_EQ(wait_driver(start_driver(2, "resume", dataset, run, "resume.log")), 0)
      << log_text(run / "resume.log");

  // Every candidate committed exactly once over both runs.
  const Journal::Contents contents = Journal::read(journal);
  const std::multiset<std::uint64_t> ids(contents.done.begin(), contents.done.end());
  ASSERT_EQ(ids.size(), static_cast<std::size_t>(kCandidates));
  for (std::uint64_t id = 0; id < kCandidates; ++id) EXPECT_EQ(ids.count(id), 1u) << id;

  const DatasetReader expected(reference);
  const DatasetReader resumed(dataset);
  EXPECT_EQ(resumed.done(), std::vector<std::uint8_t>(kCandidates, 1));
  EXPECT_EQ(resumed.candidates(), expected.candidates());
  for (std::uint64_t id = 0; id < kCandidates; ++id) {
    EXPECT_EQ(resumed.trajectory(id), expected.trajectory(id)) << id;
    EXPECT_EQ(resumed.stress(id), expected.stress(id)) << id;
    EXPECT_EQ(resumed.finger_stress(id), expected.finger_stress(id)) << id;
  }
  EXPECT_TRUE(testing::file_bytes(dataset) == testing::file_bytes(reference));
}

TEST(KillAndResume, ResumedDatasetsEqualAnUninterruptedOne) {
  const fs::path folder =
      fs::temp_directory_path() / ("grip_io_kill_" + std::to_string(::getpid()));
  fs::remove_all(folder);
  fs::create_directories(folder / "reference");
  // The reference: one uninterrupted run on one rank (the bytes must not depend on the count).
  const fs::path reference = folder / "reference" / "data.h5";
  ASSERT_EQ(wait_driver(start_driver(1, "create", reference, folder / "reference", "log")), 0)
      << log_text(folder / "reference" / "log");
  for (const std::uint64_t seed : {1u, 2u, 3u, 4u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    kill_and_resume(seed, folder, reference);
  }
  if (!HasFailure()) fs::remove_all(folder);
}

}  // namespace
}  // namespace grip::io
