// A farm run killed mid-way (SIGKILL of the whole mpirun, two ranks) and resumed, one whose
// rank 1 is killed inside a work unit's commit (rows written, not yet journaled) and resumed,
// and one stopped by SIGINT and resumed, all end equal, record by record, to an uninterrupted
// run: nothing lost, nothing written twice. The test supervises `grip farm` as separate processes.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <thread>
#include <vector>

#include "io/dataset_reader.hpp"
#include "io/journal.hpp"
#include "tests/farm/farm_test_job.hpp"

namespace grip::farm {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

constexpr int kCandidates = 12;  // 3 cylinders x 4, one work unit per rank each commit

// Starts argv in its own process group with output to `log`.
pid_t start(const std::vector<std::string>& args, const fs::path& log) {
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid != 0) return pid;
  ::setpgid(0, 0);
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
  std::freopen(log.c_str(), "w", stdout);
  std::freopen(log.c_str(), "a", stderr);
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  ::execv(argv[0], argv.data());
  std::_Exit(127);
}

// The exit code (128 + signal when killed); kills the group after two minutes.
int wait_for(pid_t pid) {
  const auto deadline = std::chrono::steady_clock::now() + 120s;
  int status = 0;
  while (::waitpid(pid, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(-pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      ADD_FAILURE() << "grip farm hung and was killed";
      return -1;
    }
    std::this_thread::sleep_for(5ms);
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// Ids committed so far, per complete journal line.
std::vector<std::uint64_t> committed(const fs::path& dataset) {
  const fs::path journal = io::Journal::path_for(dataset);
  if (!fs::exists(journal)) return {};
  return io::Journal::read(journal).done;
}

// Waits until the journal holds at least one committed round (or the process ended).
void wait_for_first_commit(pid_t pid, const fs::path& dataset) {
  const auto deadline = std::chrono::steady_clock::now() + 120s;
  while (committed(dataset).empty() && std::chrono::steady_clock::now() < deadline) {
    int status = 0;
    if (::waitpid(pid, &status, WNOHANG) == pid) {
      FAIL() << "grip farm ended before its first commit";
    }
    std::this_thread::sleep_for(2ms);
  }
}

// Waits until no process names `dataset` on its command line: the ranks of a killed mpirun
// outlive it until they notice, and hold the journal's lock until then.
void wait_until_gone(const fs::path& dataset) {
  const auto deadline = std::chrono::steady_clock::now() + 60s;
  for (;;) {
    bool found = false;
    for (const auto& entry : fs::directory_iterator("/proc")) {
      std::ifstream in(entry.path() / "cmdline", std::ios::binary);
      std::stringstream text;
      text << in.rdbuf();
      found = found || text.str().find(dataset.string()) != std::string::npos;
    }
    if (!found) return;
    if (std::chrono::steady_clock::now() > deadline) {
      ADD_FAILURE() << "the killed run's ranks did not end";
      return;
    }
    std::this_thread::sleep_for(10ms);
  }
}

std::string log_text(const fs::path& log) {
  std::ifstream in(log);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class FarmResume : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("grip_farm_resume_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    job_ = dir_ / "small.toml";
    testing::write_file(job_, testing::small_job(3, 4, false));
    const fs::path log = dir_ / "reference.log";
    ASSERT_EQ(wait_for(start({GRIP_EXECUTABLE, "farm", job_.string(), "--output",
                              (dir_ / "reference.h5").string(), "--threads", "1"},
                             log)),
              0)
        << log_text(log);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::vector<std::string> farm(const fs::path& dataset, bool resume, bool mpi) const {
    std::vector<std::string> args;
    if (mpi) args = {GRIP_MPIEXEC, "-np", "2", "--oversubscribe"};
    for (const std::string& a :
         {std::string(GRIP_EXECUTABLE), std::string("farm"), job_.string(), std::string("--output"),
          dataset.string(), std::string("--threads"), std::string("1"), std::string("--batch"),
          std::string("1")}) {
      args.push_back(a);
    }
    if (resume) args.push_back("--resume");
    return args;
  }

  // Every candidate committed exactly once over all runs' journal lines.
  void expect_each_once(const fs::path& dataset) const {
    const std::vector<std::uint64_t> ids = committed(dataset);
    EXPECT_EQ(ids.size(), static_cast<std::size_t>(kCandidates));
    EXPECT_EQ(std::set<std::uint64_t>(ids.begin(), ids.end()).size(), ids.size());
  }

  fs::path dir_, job_;
};

TEST_F(FarmResume, KilledUnderMpirunThenResumedEqualsUninterrupted) {
  const fs::path dataset = dir_ / "killed.h5";
  const pid_t pid = start(farm(dataset, false, true), dir_ / "killed.log");
  wait_for_first_commit(pid, dataset);
  ::kill(-pid, SIGKILL);  // mpirun and what shares its process group, mid-run
  wait_for(pid);
  wait_until_gone(dataset);
  const std::size_t before = committed(dataset).size();
  EXPECT_GT(before, 0u);
  EXPECT_LT(before, static_cast<std::size_t>(kCandidates)) << "the run ended before the kill";

  const fs::path log = dir_ / "resumed.log";
  ASSERT_EQ(wait_for(start(farm(dataset, true, true), log)), 0) << log_text(log);
  testing::expect_same_dataset(dir_ / "reference.h5", dataset);
  expect_each_once(dataset);
}

// Rank 1 kills itself in the sync of its second work unit (a preload on rank 1 only): that
// unit's rows and done flags are in the file, its journal line is not. The resumed run redoes
// the unit and rewrites its rows identically.
TEST_F(FarmResume, RankKilledMidCommitThenResumedEqualsUninterrupted) {
  const fs::path dataset = dir_ / "mid_commit.h5";
  const std::vector<std::string> grip = farm(dataset, false, false);
  std::vector<std::string> args = {GRIP_MPIEXEC, "--oversubscribe", "-np", "1"};
  args.insert(args.end(), grip.begin(), grip.end());
  for (const std::string& a : {std::string(":"), std::string("-np"), std::string("1"),
                               std::string("-x"), std::string("LD_PRELOAD=") + GRIP_KILL_MID_COMMIT,
                               std::string("-x"), std::string("GRIP_KILL_AT_DATASET_SYNC=2")}) {
    args.push_back(a);
  }
  args.insert(args.end(), grip.begin(), grip.end());
  const fs::path killed_log = dir_ / "mid_commit.log";
  EXPECT_NE(wait_for(start(args, killed_log)), 0) << log_text(killed_log);
  wait_until_gone(dataset);
  const std::vector<std::uint64_t> journaled = committed(dataset);
  const std::set<std::uint64_t> in_journal(journaled.begin(), journaled.end());
  EXPECT_LT(in_journal.size(), static_cast<std::size_t>(kCandidates));
  const std::vector<std::uint8_t> flags = io::DatasetReader(dataset).done();
  std::size_t written_not_journaled = 0;
  for (std::uint64_t id = 0; id < flags.size(); ++id) {
    written_not_journaled += flags[id] != 0 && in_journal.count(id) == 0;
  }
  EXPECT_GE(written_not_journaled, 1u) << "rank 1 was not killed between its write and journal";

  const fs::path log = dir_ / "resumed.log";
  ASSERT_EQ(wait_for(start(farm(dataset, true, true), log)), 0) << log_text(log);
  testing::expect_same_dataset(dir_ / "reference.h5", dataset);
  expect_each_once(dataset);
}

TEST_F(FarmResume, StoppedBySigintThenResumedEqualsUninterrupted) {
  const fs::path dataset = dir_ / "stopped.h5";
  const fs::path log = dir_ / "stopped.log";
  const pid_t pid = start(farm(dataset, false, false), log);
  wait_for_first_commit(pid, dataset);
  ::kill(pid, SIGINT);
  EXPECT_EQ(wait_for(pid), 130) << log_text(log);
  EXPECT_NE(log_text(log).find("--resume"), std::string::npos) << log_text(log);
  EXPECT_LT(committed(dataset).size(), static_cast<std::size_t>(kCandidates));

  const fs::path resumed = dir_ / "resumed.log";
  ASSERT_EQ(wait_for(start(farm(dataset, true, false), resumed)), 0) << log_text(resumed);
  testing::expect_same_dataset(dir_ / "reference.h5", dataset);
  expect_each_once(dataset);
}

// Whether `pid` has a handler of its own for `signal` (its /proc status's caught-signal mask).
bool catches(pid_t pid, int signal) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("SigCgt:", 0) == 0) {
      return (std::stoull(line.substr(7), nullptr, 16) >> (signal - 1)) & 1;
    }
  }
  return false;
}

// Planning holds nothing to commit and may take hours for a large job: a stop signal then ends
// the run at once, and no dataset is created.
TEST(FarmStop, ASignalWhilePlanningEndsTheRunAtOnceAndCreatesNothing) {
  const fs::path dir = fs::temp_directory_path() / ("grip_farm_stop_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path job = dir / "large.toml";
  testing::write_file(job, testing::small_job(1, 200'000, false));  // hours of synthesis
  const fs::path dataset = dir / "large.h5", log = dir / "large.log";
  const pid_t pid = start(
      {GRIP_EXECUTABLE, "farm", job.string(), "--output", dataset.string(), "--threads", "1"}, log);
  const auto deadline = std::chrono::steady_clock::now() + 60s;
  while (!catches(pid, SIGINT) && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(2ms);
  }
  std::this_thread::sleep_for(500ms);  // into planning
  ::kill(pid, SIGINT);
  EXPECT_EQ(wait_for(pid), 130) << log_text(log);
  EXPECT_NE(log_text(log).find("stopped before any trial ran; nothing was written"),
            std::string::npos)
      << log_text(log);
  EXPECT_FALSE(fs::exists(dataset));
  EXPECT_FALSE(fs::exists(io::Journal::path_for(dataset)));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace grip::farm
