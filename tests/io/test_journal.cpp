// The checkpoint journal alone: header and done lines round-trip, a torn last line is ignored
// and cut on reopen, damage elsewhere is an error naming the line, and an existing journal is
// never overwritten.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "io/dataset_error.hpp"
#include "io/journal.hpp"
#include "tests/io/io_test_files.hpp"

namespace grip::io {
namespace {

namespace fs = std::filesystem;

class JournalTest : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() / ("grip_io_journal_" + std::to_string(::getpid()));
    fs::remove_all(folder_);
    fs::create_directories(folder_);
    path_ = Journal::path_for(folder_ / "data.h5");
  }
  void TearDown() override { fs::remove_all(folder_); }

  fs::path folder_;
  fs::path path_;
};

TEST_F(JournalTest, SitsBesideItsDataset) {
  EXPECT_EQ(Journal::path_for("/x/data.h5"), fs::path("/x/data.h5.journal"));
}

TEST_F(JournalTest, RoundTripsHeaderAndBatches) {
  {
    Journal journal = Journal::create(path_, "feed", 10);
    const std::vector<std::uint64_t> first{3, 1};
    const std::vector<std::uint64_t> second{9};
    journal.append(first);
    journal.append(second);
  }
  EXPECT_FALSE(fs::exists(path_.string() + ".tmp"));
  const Journal::Contents contents = Journal::read(path_);
  EXPECT_EQ(contents.job_id, "feed");
  EXPECT_EQ(contents.candidate_count, 10u);
  EXPECT_EQ(contents.done, (std::vector<std::uint64_t>{3, 1, 9}));
  EXPECT_EQ(contents.valid_bytes, fs::file_size(path_));
}

TEST_F(JournalTest, IgnoresATornLastLineAndCutsItOnReopen) {
  { Journal::create(path_, "feed", 10).append(std::vector<std::uint64_t>{4, 5}); }
  const auto complete = fs::file_size(path_);
  std::ofstream(path_, std::ios::app) << "done 2 6";  // a crash mid-line
  const Journal::Contents contents = Journal::read(path_);
  EXPECT_EQ(contents.done, (std::vector<std::uint64_t>{4, 5}));
  EXPECT_EQ(contents.valid_bytes, complete);
  { Journal::reopen(path_, contents.valid_bytes).append(std::vector<std::uint64_t>{6, 7}); }
  EXPECT_EQ(Journal::read(path_).done, (std::vector<std::uint64_t>{4, 5, 6, 7}));
}

TEST_F(JournalTest, ADamagedLineIsAnErrorNamingIt) {
  { Journal::create(path_, "feed", 10).append(std::vector<std::uint64_t>{1}); }
  std::ofstream(path_, std::ios::app) << "done 2 7\ndone 1 8\n";  // line 5 lists too few ids
  try {
    Journal::read(path_);
    FAIL() << "a damaged journal was accepted";
  } catch (const DatasetError& e) {
    EXPECT_NE(std::string(e.what()).find(path_.string() + ":5:"), std::string::npos) << e.what();
  }
}

TEST_F(JournalTest, AnIdOutsideTheDatasetIsAnError) {
  { Journal::create(path_, "feed", 10).append(std::vector<std::uint64_t>{10}); }
  EXPECT_THROW(Journal::read(path_), DatasetError);
}

TEST_F(JournalTest, AMissingOrHeaderlessJournalSaysTheDatasetWasNotFinished) {
  EXPECT_THROW(Journal::read(path_), DatasetError);
  testing::write_bytes(path_, "grip-journal 1\njob feed\n");
  try {
    Journal::read(path_);
    FAIL() << "a headerless journal was accepted";
  } catch (const DatasetError& e) {
    EXPECT_NE(std::string(e.what()).find("never completely created"), std::string::npos);
  }
}

// While one run holds its journal open, another cannot take it (a second resume, or the
// ranks of a killed mpirun still writing); once the first lets go, it can, the bytes unchanged.
TEST_F(JournalTest, OneWriterAtATime) {
  std::string bytes;
  {
    Journal first = Journal::create(path_, "feed", 10);
    first.append(std::vector<std::uint64_t>{2});
    bytes = testing::file_bytes(path_);
    try {
      Journal::reopen(path_, Journal::read(path_).valid_bytes);
      ADD_FAILURE() << "a second writer took the journal";
    } catch (const DatasetError& e) {
      EXPECT_NE(std::string(e.what()).find("another grip run"), std::string::npos) << e.what();
    }
    EXPECT_EQ(testing::file_bytes(path_), bytes);
  }
  Journal second = Journal::reopen(path_, Journal::read(path_).valid_bytes);
  EXPECT_EQ(testing::file_bytes(path_), bytes);
}

TEST_F(JournalTest, CreateNeverOverwrites) {
  testing::write_bytes(path_, "precious");
  EXPECT_THROW(Journal::create(path_, "feed", 1), DatasetError);
  EXPECT_EQ(testing::file_bytes(path_), "precious");
}

}  // namespace
}  // namespace grip::io
