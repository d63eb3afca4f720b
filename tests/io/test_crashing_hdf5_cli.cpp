// A dataset file that crashes HDF5 itself (1.10.8, found by fuzz_dataset): one byte of a
// one-candidate dataset marks a dataset's fill-value message as shared, and H5Dopen2 then reads
// through a null pointer. `grip inspect` and `grip farm --resume` (one process and two ranks)
// read it in a child process first: one error naming the file, exit 1, both files unchanged.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "io/journal.hpp"
#include "tests/app/run_grip.hpp"

namespace grip::io {
namespace {

namespace fs = std::filesystem;
using grip::testing::count_lines;
using grip::testing::count_of;
using grip::testing::GripRun;
using grip::testing::quoted;
using grip::testing::run_command;
using grip::testing::run_grip;
using grip::testing::slurp;

// The byte, in the dataset the writer driver makes for one candidate: the flags of the first
// fill-value message (type 5, 8 bytes), 1 (constant) in the file, 3 (constant, shared) here.
constexpr std::size_t kFillValueFlags = 9020;

std::size_t hash_of(const fs::path& file) { return std::hash<std::string>{}(slurp(file)); }

class CrashingHdf5File : public ::testing::Test {
 protected:
  void SetUp() override {
    ::setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
    ::setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
    // Under AddressSanitizer (scripts/sanitize.sh) a crash is ASan's report and exit 1, not
    // death by the signal the probe contains: the grip processes these tests start keep the
    // signals as a release build gets them. Without ASan the variable is not read.
    const char* asan = std::getenv("ASAN_OPTIONS");
    ::setenv("ASAN_OPTIONS",
             ((asan ? std::string(asan) + ":" : std::string()) + "handle_segv=0:handle_sigbus=0")
                 .c_str(),
             1);
    dir_ = fs::temp_directory_path() / ("grip_io_crashing_hdf5_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    dataset_ = dir_ / "data.h5";
    const std::string make = std::string(GRIP_MPIEXEC) + " -np 1 " + GRIP_WRITER_DRIVER +
                             " create " + quoted(dataset_) + " " + quoted(dir_) + " 1 >/dev/null";
    ASSERT_EQ(std::system(make.c_str()), 0);
    std::fstream file(dataset_, std::ios::in | std::ios::out | std::ios::binary);
    file.seekg(kFillValueFlags);
    ASSERT_EQ(file.get(), 1) << "the writer's file changed: find a new crashing byte with "
                                "scripts/fuzz.sh 60 fuzz_dataset";
    file.seekp(kFillValueFlags);
    file.put(3);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path dir_, dataset_;
};

// The premise: reading the file kills the reading process (here grip's hidden probe mode).
TEST_F(CrashingHdf5File, ReadingItCrashesHdf5) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    std::freopen("/dev/null", "w", stderr);
    ::execl(GRIP_EXECUTABLE, "grip", "--probe-dataset", dataset_.c_str(),
            static_cast<char*>(nullptr));
    std::_Exit(127);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  EXPECT_TRUE(WIFSIGNALED(status)) << "HDF5 reads the file now: the tests below prove nothing";
}

TEST_F(CrashingHdf5File, InspectSaysTheFileIsDamaged) {
  const std::size_t before = hash_of(dataset_);
  const GripRun run = run_grip("inspect " + quoted(dataset_));
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_EQ(count_lines(run.err), 1) << run.err;
  EXPECT_NE(run.err.find(dataset_.string() +
                         ": the file is damaged: HDF5 cannot read it (reading it crashed the "
                         "reader: Segmentation fault); nothing was changed"),
            std::string::npos)
      << run.err;
  EXPECT_TRUE(run.out.empty()) << run.out;
  EXPECT_EQ(hash_of(dataset_), before);
}

TEST_F(CrashingHdf5File, ResumeRefusesItOnOneRankAndOnTwo) {
  const fs::path job = dir_ / "job.toml";
  std::ofstream(job) << "[job]\nname = \"crash\"\n\n[[objects]]\ncategory = \"cylinder\"\n\n"
                        "[[grippers]]\nname = \"parallel-jaw\"\ncandidates = 1\n";
  const std::size_t before = hash_of(dataset_);
  const std::size_t journal_before = hash_of(Journal::path_for(dataset_));
  const std::string farm = std::string(GRIP_EXECUTABLE) + " farm " + quoted(job) + " --output " +
                           quoted(dataset_) + " --resume --threads 1";
  for (const char* launcher : {"", GRIP_MPIEXEC " -np 2 --oversubscribe "}) {
    const GripRun run = run_command(launcher + farm);
    EXPECT_EQ(run.exit_code, 1) << launcher << run.err;
    EXPECT_EQ(count_of(run.err, "[error]"), 1) << launcher << run.err;
    EXPECT_NE(run.err.find(dataset_.string() +
                           ": the file is damaged: HDF5 cannot read it (reading it crashed the "
                           "reader: Segmentation fault); nothing was changed"),
              std::string::npos)
        << launcher << run.err;
    EXPECT_EQ(run.err.find("MPI_ABORT"), std::string::npos) << run.err;
    EXPECT_EQ(hash_of(dataset_), before) << launcher;
    EXPECT_EQ(hash_of(Journal::path_for(dataset_)), journal_before) << launcher;
  }
}

}  // namespace
}  // namespace grip::io
