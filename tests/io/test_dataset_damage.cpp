// Hostile dataset files under two MPI ranks: stored indices out of range, shapes and size
// attributes that disagree, plan columns changed in range, and bytes flipped in committed rows.
// Reading names the file, dataset, row, value and valid range; a refused resume changes no byte;
// damaged committed rows are found, not counted as done, and redone by resume.
#include <gtest/gtest.h>
#include <mpi.h>

#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "io/dataset_error.hpp"
#include "io/dataset_reader.hpp"
#include "io/dataset_summary.hpp"
#include "io/dataset_writer.hpp"
#include "io/journal.hpp"
#include "tests/io/damage_dataset.hpp"
#include "tests/io/io_test_files.hpp"
#include "tests/io/synthetic_dataset.hpp"

namespace grip::io {
namespace {

using testing::file_bytes;
using testing::world_rank;

constexpr std::uint64_t kSeed = 5;
const std::string kJob = "[job]\nname = \"damaged\"\n";

Provenance provenance() { return testing::synthetic_provenance(kJob, kSeed); }

// Commits `rounds` of ids, each round's ids split between the two ranks by parity.
void write_rounds(DatasetWriter& writer, const std::vector<std::vector<std::uint64_t>>& rounds) {
  for (const auto& round : rounds) {
    std::vector<CandidateResult> mine;
    for (const std::uint64_t id : round) {
      if (static_cast<int>(id % 2) == world_rank()) {
        mine.push_back(testing::synthetic_result(writer.layout(), id, kSeed));
      }
    }
    writer.write(mine);
  }
}

void make_dataset(const std::filesystem::path& path, std::uint32_t candidates,
                  const std::vector<std::vector<std::uint64_t>>& rounds) {
  DatasetWriter writer = DatasetWriter::create(path, testing::synthetic_plan(candidates),
                                               provenance(), MPI_COMM_WORLD);
  write_rounds(writer, rounds);
}

// Damages the file on rank 0 while the other ranks wait (whatever happens, every rank goes on
// to the same next collective call).
template <typename Damage>
void on_rank_zero(Damage&& damage) {
  MPI_Barrier(MPI_COMM_WORLD);
  if (world_rank() == 0) {
    try {
      damage();
    } catch (const std::exception& e) {
      ADD_FAILURE() << e.what();
    }
  }
  MPI_Barrier(MPI_COMM_WORLD);
}

std::string read_error(const std::filesystem::path& path) {
  try {
    const DatasetReader reader(path);
    reader.provenance();
    for (std::uint32_t o = 0; o < reader.layout().objects.size(); ++o) reader.object(o);
    for (std::uint32_t g = 0; g < reader.layout().grippers.size(); ++g) reader.gripper(g);
  } catch (const DatasetError& e) {
    return e.what();
  }
  return "";
}

// A resume that every rank refuses with `message` (after the file's name), leaving the
// dataset and its journal byte-identical; and a reader that refuses the file alike.
void expect_refused(const std::filesystem::path& path, const std::string& message) {
  MPI_Barrier(MPI_COMM_WORLD);
  const std::string before = file_bytes(path);
  const std::string journal_before = file_bytes(Journal::path_for(path));
  MPI_Barrier(MPI_COMM_WORLD);
  try {
    DatasetWriter::resume(path, provenance(), MPI_COMM_WORLD);
    ADD_FAILURE() << "resume of " << path << " was not refused";
  } catch (const DatasetError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path.string() + ": cannot resume: " + message), std::string::npos) << what;
    EXPECT_NE(what.find("nothing was changed"), std::string::npos) << what;
  }
  MPI_Barrier(MPI_COMM_WORLD);
  EXPECT_TRUE(file_bytes(path) == before) << "a refused resume changed " << path;
  EXPECT_TRUE(file_bytes(Journal::path_for(path)) == journal_before);
  if (world_rank() == 0) {
    const std::string error = read_error(path);
    EXPECT_NE(error.find(path.string() + ": " + message), std::string::npos) << error;
  }
  MPI_Barrier(MPI_COMM_WORLD);
}

// A fresh partial dataset of 10 candidates (0 to 2 committed) for each damage.
class DamagedDataset : public ::testing::Test {
 protected:
  std::filesystem::path fresh(const std::string& name) {
    const auto path = testing::shared_scratch(MPI_COMM_WORLD, "damaged_" + name) / "data.h5";
    make_dataset(path, 10, {{0, 1, 2}});
    return path;
  }
};

TEST_F(DamagedDataset, IndicesOutOfRangeAreRefusedNamingTheDatasetRowValueAndRange) {
  // The synthetic plan: 3 objects, 2 grippers; candidate 5 is object 2 with gripper 1.
  auto path = fresh("object");
  on_rank_zero(
      [&] { testing::set_element<std::uint32_t>(path, "/candidates/object", 5, 4000000000u); });
  expect_refused(path,
                 "/candidates/object row 5 is 4000000000, outside the 3 objects (valid: 0 to 2)");

  path = fresh("gripper");
  on_rank_zero([&] { testing::set_element<std::uint32_t>(path, "/candidates/gripper", 5, 77); });
  expect_refused(path, "/candidates/gripper row 5 is 77, outside the 2 grippers (valid: 0 to 1)");

  // Object 0 and gripper 0 hold the trajectories of candidates 0 and 6.
  path = fresh("frame_slot");
  on_rank_zero([&] { testing::set_element<std::int64_t>(path, "/candidates/frame_slot", 6, 99); });
  expect_refused(path,
                 "/candidates/frame_slot row 6 is 99, outside the 2 rows of "
                 "/objects/000000/trajectories/000 (valid: -1, or 0 to 1)");

  path = fresh("stress_slot");
  on_rank_zero([&] { testing::set_element<std::int64_t>(path, "/candidates/stress_slot", 4, -7); });
  expect_refused(path, "/candidates/stress_slot row 4 is -7, outside the ");

  // Gripper 1 (two rigid hands) has no finger stress rows.
  path = fresh("finger_stress_slot");
  on_rank_zero(
      [&] { testing::set_element<std::int64_t>(path, "/candidates/finger_stress_slot", 3, 0); });
  expect_refused(path,
                 "/candidates/finger_stress_slot row 3 is 0, outside the 0 rows of "
                 "/grippers/001/finger_stress (valid: -1)");
}

TEST_F(DamagedDataset, ShapesAndSizeAttributesThatDisagreeAreRefused) {
  auto path = fresh("hands");
  on_rank_zero([&] { testing::set_attribute(path, "/grippers/001", "hands", 77); });
  expect_refused(path, "attribute 'hands' of /grippers/001 is 77 (valid: 1 to 2)");

  path = fresh("shape");
  on_rank_zero([&] { testing::replace_with_rows(path, "/candidates/d1", 4); });
  expect_refused(path, "/candidates/d1 has shape (4), expected (10)");
}

TEST_F(DamagedDataset, PlanColumnsChangedWithinRangeFailTheirChecksum) {
  // Candidate 1 moved to gripper 1 (in range: it has no trajectory or finger stress slot).
  const auto path = fresh("plan_checksum");
  on_rank_zero([&] { testing::set_element<std::uint32_t>(path, "/candidates/gripper", 1, 1); });
  expect_refused(path,
                 "/candidates/gripper does not match the checksum written when the dataset "
                 "was created");
}

TEST_F(DamagedDataset, MeshesChangedAfterCreationFailTheirChecksum) {
  const auto path = fresh("mesh");
  on_rank_zero([&] { testing::flip_byte(path, "/objects/000001/vertices", 17); });
  if (world_rank() == 0) {
    EXPECT_NE(read_error(path).find(path.string() +
                                    ": /objects/000001/vertices does not match the checksum "
                                    "written when the dataset was created"),
              std::string::npos)
        << read_error(path);
  }
}

// The byte at element `element` of candidate `id`'s row of a trajectory column.
std::size_t trajectory_byte(const DatasetLayout& layout, std::uint64_t id, std::size_t element) {
  const std::uint64_t vertices = layout.objects[layout.object[id]].vertices;
  const std::uint64_t row = layout.frames() * vertices * 3;
  return (static_cast<std::uint64_t>(layout.frame_slot[id]) * row + element) * sizeof(float) + 2;
}

TEST_F(DamagedDataset, FlippedBytesInCommittedRowsAreReportedAndRedoneByResume) {
  const auto folder = testing::shared_scratch(MPI_COMM_WORLD, "damaged_rows");
  const auto path = folder / "data.h5";
  const auto reference = folder / "reference.h5";
  std::vector<std::uint64_t> all;
  for (std::uint64_t id = 0; id < 12; ++id) all.push_back(id);
  make_dataset(reference, 12, {all});
  // Three rounds; 9 to 11 stay pending.
  make_dataset(path, 12, {{0, 1, 2}, {3, 4, 5, 6}, {7, 8}});
  // A bit flips in a contact force of candidate 4 (object 1, gripper 1, committed in round 2)
  // and in the d1 of candidate 7 (round 3).
  on_rank_zero([&] {
    const std::size_t byte = trajectory_byte(DatasetReader(path).layout(), 4, 5);
    testing::flip_byte(path, "/objects/000001/trajectories/001/contact_forces", byte);
    testing::flip_byte(path, "/candidates/d1", 7 * sizeof(double));
  });
  const std::vector<Damage> expected = {{4, "/objects/000001/trajectories/001/contact_forces"},
                                        {7, "/candidates/d1"}};
  const auto same = [](const std::vector<Damage>& a, const std::vector<Damage>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (a[i].candidate != b[i].candidate || a[i].dataset != b[i].dataset) return false;
    }
    return true;
  };
  if (world_rank() == 0) {
    const DatasetReader reader(path);
    EXPECT_EQ(reader.done(), (std::vector<std::uint8_t>{1, 1, 1, 1, 1, 1, 1, 1, 1, 0, 0, 0}));
    EXPECT_TRUE(same(reader.damage(), expected));
    const DatasetSummary summary = summarize(reader);
    EXPECT_EQ(summary.done, 7u);  // 9 committed, 2 of them damaged
    std::vector<Damage> reported;
    std::vector<std::uint64_t> rounds;
    for (const DamagedRow& row : summary.damaged) {
      reported.push_back(row.damage);
      rounds.push_back(row.round);
    }
    EXPECT_TRUE(same(reported, expected));
    EXPECT_EQ(rounds, (std::vector<std::uint64_t>{2, 3}));
  }
  {
    DatasetWriter writer = DatasetWriter::resume(path, provenance(), MPI_COMM_WORLD);
    EXPECT_EQ(writer.pending(), (std::vector<std::uint64_t>{4, 7, 9, 10, 11}));
    if (world_rank() == 0) {
      EXPECT_TRUE(same(writer.damaged(), expected));
    }
    write_rounds(writer, {writer.pending()});
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (world_rank() == 0) {
    const DatasetReader reader(path);
    EXPECT_TRUE(reader.damage().empty());
    EXPECT_EQ(summarize(reader).done, 12u);
    EXPECT_TRUE(file_bytes(path) == file_bytes(reference))
        << "the redone dataset differs from an undamaged run's";
    const DatasetReader undamaged(reference);
    EXPECT_EQ(reader.candidates(), undamaged.candidates());
    for (std::uint64_t id = 0; id < 12; ++id) {
      EXPECT_EQ(reader.trajectory(id), undamaged.trajectory(id)) << id;
      EXPECT_EQ(reader.stress(id), undamaged.stress(id)) << id;
      EXPECT_EQ(reader.finger_stress(id), undamaged.finger_stress(id)) << id;
    }
  }
  MPI_Barrier(MPI_COMM_WORLD);
}

}  // namespace
}  // namespace grip::io
