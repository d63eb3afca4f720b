// The dataset fuzz targets' seeds: fuzz_dataset's valid dataset must be of the current format
// (a seed of an older one stops at the version check and fuzzes nothing past it), and
// fuzz_dataset_values' seed must be that dataset's stored values, so that mutating it reaches
// the values grip checks.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz/dataset_storage.hpp"
#include "io/dataset_error.hpp"
#include "io/dataset_reader.hpp"
#include "io/dataset_summary.hpp"

namespace {

const std::filesystem::path kTemplate =
    std::filesystem::path(GRIP_SOURCE_DIR) / "fuzz/corpus/fuzz_dataset/four_candidates.h5";
const std::filesystem::path kValuesSeed =
    std::filesystem::path(GRIP_SOURCE_DIR) / "fuzz/corpus/fuzz_dataset_values/template_values.bin";

std::vector<std::uint8_t> bytes_of(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

std::filesystem::path write_file(const std::vector<std::uint8_t>& bytes, const std::string& name) {
  const std::filesystem::path file = std::filesystem::path(testing::TempDir()) / name;
  std::ofstream(file, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
  return file;
}

TEST(FuzzDatasetSeeds, TheValidDatasetIsOfTheCurrentFormatAndReadsWhole) {
  const grip::io::DatasetReader reader(kTemplate);
  const grip::io::DatasetSummary summary = grip::io::summarize(reader);
  EXPECT_EQ(summary.candidates, 4u);
  EXPECT_EQ(summary.done, 4u);
  EXPECT_TRUE(summary.damaged.empty());
  // What the values target mutates covers trajectories, stress, finger stress and a two-hand
  // gripper.
  EXPECT_TRUE(reader.trajectory(0).has_value());
  EXPECT_TRUE(reader.stress(1).has_value());
  EXPECT_TRUE(reader.finger_stress(0).has_value());
  EXPECT_EQ(reader.gripper(1).hands, 2u);
}

TEST(FuzzDatasetSeeds, TheValuesSeedIsTheValidDatasetsStoredValues) {
  const std::vector<grip::fuzz::StorageRange> ranges = grip::fuzz::storage_ranges(kTemplate);
  const std::vector<std::uint8_t> file = bytes_of(kTemplate);
  EXPECT_EQ(grip::fuzz::stored_values(file, ranges), bytes_of(kValuesSeed));
  std::uint64_t previous_end = 0;
  for (const grip::fuzz::StorageRange& range : ranges) {
    EXPECT_GE(range.offset, previous_end) << "ranges overlap or are out of order";
    previous_end = range.offset + range.size;
  }
  EXPECT_LE(previous_end, file.size());
}

TEST(FuzzDatasetSeeds, AValueInputReachesTheIndicesTheReaderChecks) {
  // The values target's input replaces stored values only: all bytes 0xff make the first
  // candidate's object index 4294967295, which the reader refuses by name, HDF5's structure
  // being intact.
  const std::vector<grip::fuzz::StorageRange> ranges = grip::fuzz::storage_ranges(kTemplate);
  std::vector<std::uint8_t> file = bytes_of(kTemplate);
  const std::vector<std::uint8_t> values(grip::fuzz::stored_values(file, ranges).size(), 0xff);
  grip::fuzz::overwrite_values(file, ranges, values.data(), values.size());
  try {
    grip::io::DatasetReader reader(write_file(file, "all_ff.h5"));
    grip::io::summarize(reader);
    FAIL() << "a dataset whose stored values are all 0xff was read";
  } catch (const grip::io::DatasetError& error) {
    EXPECT_NE(std::string(error.what()).find("outside the"), std::string::npos) << error.what();
  }
}

}  // namespace
