// `grip inspect` and `grip farm --resume` on a small farm job's dataset damaged by HDF5 API
// writes: an out-of-range object index, a gripper index of 77, a flipped byte in a contact
// force. Bad indices are one message naming the file, dataset, row, value and valid range, with
// exit 1 and the files byte-identical afterwards; a damaged committed row is reported by inspect
// (exit 1, the file, candidate, journal line and dataset named) and redone by resume.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <functional>
#include <string>

#include "io/dataset_reader.hpp"
#include "io/journal.hpp"
#include "tests/app/run_grip.hpp"
#include "tests/farm/farm_test_job.hpp"
#include "tests/io/damage_dataset.hpp"

namespace grip::io {
namespace {

namespace fs = std::filesystem;
using grip::testing::GripRun;
using grip::testing::quoted;
using grip::testing::run_grip;
using grip::testing::slurp;

std::size_t hash_of(const fs::path& file) { return std::hash<std::string>{}(slurp(file)); }

// A finished dataset of 3 objects x 4 candidates with trajectories, committed 2 candidates a
// round, made once per test; each test damages a copy.
class DamagedDatasetCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("grip_io_damaged_cli_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    job_ = dir_ / "small.toml";
    farm::testing::write_file(job_, farm::testing::small_job(3, 4, false));
    const GripRun run = farm("reference.h5", false);
    ASSERT_EQ(run.exit_code, 0) << run.err;
  }
  void TearDown() override { fs::remove_all(dir_); }

  GripRun farm(const std::string& dataset, bool resume) const {
    return run_grip("farm " + quoted(job_) + " --output " + quoted(dir_ / dataset) +
                    " --threads 1 --batch 2" + (resume ? " --resume" : ""));
  }

  // A copy of the reference dataset and its journal.
  fs::path copy(const std::string& name) const {
    const fs::path path = dir_ / name;
    fs::copy_file(dir_ / "reference.h5", path);
    fs::copy_file(Journal::path_for(dir_ / "reference.h5"), Journal::path_for(path));
    return path;
  }

  fs::path dir_, job_;
};

TEST_F(DamagedDatasetCli, InspectRefusesAnObjectIndexOutOfRange) {
  const fs::path dataset = copy("object.h5");
  testing::set_element<std::uint32_t>(dataset, "/candidates/object", 1, 4000000000u);
  const std::size_t before = hash_of(dataset);
  const GripRun run = run_grip("inspect " + quoted(dataset));
  EXPECT_EQ(run.exit_code, 1) << run.out;
  EXPECT_EQ(grip::testing::count_lines(run.err), 1) << run.err;
  EXPECT_NE(run.err.find(dataset.string() +
                         ": /candidates/object row 1 is 4000000000, outside the 3 objects "
                         "(valid: 0 to 2)"),
            std::string::npos)
      << run.err;
  EXPECT_EQ(hash_of(dataset), before);
}

TEST_F(DamagedDatasetCli, ResumeRefusesAGripperIndexOf77BeforeWritingAnything) {
  const fs::path dataset = copy("gripper.h5");
  testing::set_element<std::uint32_t>(dataset, "/candidates/gripper", 7, 77);
  const std::size_t before = hash_of(dataset);
  const std::size_t journal_before = hash_of(Journal::path_for(dataset));
  const GripRun run = farm("gripper.h5", true);
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_NE(run.err.find(dataset.string() +
                         ": cannot resume: /candidates/gripper row 7 is 77, outside the 1 "
                         "gripper (valid: 0 to 0); nothing was changed"),
            std::string::npos)
      << run.err;
  EXPECT_EQ(hash_of(dataset), before) << "a refused resume changed the dataset";
  EXPECT_EQ(hash_of(Journal::path_for(dataset)), journal_before);

  const GripRun inspect = run_grip("inspect " + quoted(dataset));
  EXPECT_EQ(inspect.exit_code, 1);
  EXPECT_NE(inspect.err.find(dataset.string() + ": /candidates/gripper row 7 is 77"),
            std::string::npos)
      << inspect.err;
}

TEST_F(DamagedDatasetCli, AFlippedContactForceIsReportedByInspectAndRedoneByResume) {
  const fs::path dataset = copy("flipped.h5");
  // Candidate 5 (object 1, journaled on line 3: lines of 2 candidates) keeps its trajectory.
  std::size_t byte = 0;
  {
    const DatasetReader reader(dataset);
    ASSERT_TRUE(reader.trajectory(5));
    const DatasetLayout& layout = reader.layout();
    const std::uint64_t row = layout.frames() * layout.objects[1].vertices * 3;
    byte = (static_cast<std::uint64_t>(layout.frame_slot[5]) * row + 7) * sizeof(float) + 1;
  }
  testing::flip_byte(dataset, "/objects/000001/trajectories/000/contact_forces", byte);

  const GripRun inspect = run_grip("inspect " + quoted(dataset));
  EXPECT_EQ(inspect.exit_code, 1);
  EXPECT_NE(inspect.out.find("candidates  12 (11 done, 1 pending)"), std::string::npos)
      << inspect.out;
  EXPECT_NE(inspect.out.find("damaged     1 committed candidates"), std::string::npos)
      << inspect.out;
  EXPECT_NE(inspect.err.find(dataset.string() +
                             ": candidate 5 (journal line 3): "
                             "/objects/000001/trajectories/000/contact_forces does not match the "
                             "checksum written with it"),
            std::string::npos)
      << inspect.err;

  const GripRun resume = farm("flipped.h5", true);
  EXPECT_EQ(resume.exit_code, 0) << resume.err;
  EXPECT_NE(resume.err.find("1 committed rows do not match their checksums"), std::string::npos)
      << resume.err;
  farm::testing::expect_same_dataset(dir_ / "reference.h5", dataset);
  const GripRun after = run_grip("inspect " + quoted(dataset));
  EXPECT_EQ(after.exit_code, 0) << after.err;
  EXPECT_NE(after.out.find("candidates  12 (12 done, 0 pending)"), std::string::npos) << after.out;
}

}  // namespace
}  // namespace grip::io
