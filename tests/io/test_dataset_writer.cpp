// The dataset writer under two real MPI ranks: exact read-back, bytes independent of which rank
// wrote a record and of collective or per-unit commits, one commit per record, resume, and
// resumes it must refuse without changing a byte.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "io/dataset_error.hpp"
#include "io/dataset_reader.hpp"
#include "io/dataset_writer.hpp"
#include "io/journal.hpp"
#include "tests/io/io_test_files.hpp"
#include "tests/io/synthetic_dataset.hpp"

namespace grip::io {
namespace {

using testing::file_bytes;
using testing::synthetic_plan;
using testing::synthetic_provenance;
using testing::synthetic_result;
using testing::world_rank;

constexpr std::uint64_t kSeed = 7;
const std::string kJob = "[job]\nname = \"synthetic\"\n";

std::vector<CandidateResult> results_for(const DatasetLayout& layout,
                                         const std::vector<std::uint64_t>& ids) {
  std::vector<CandidateResult> results;
  for (const std::uint64_t id : ids) results.push_back(synthetic_result(layout, id, kSeed));
  return results;
}

// Writes `batches`, each a list of ids per rank.
void write_batches(DatasetWriter& writer,
                   const std::vector<std::vector<std::vector<std::uint64_t>>>& batches) {
  for (const auto& batch : batches) {
    writer.write(results_for(writer.layout(), batch[static_cast<std::size_t>(world_rank())]));
  }
}

std::vector<std::uint64_t> range(std::uint64_t begin, std::uint64_t end, std::uint64_t step = 1) {
  std::vector<std::uint64_t> ids;
  for (std::uint64_t id = begin; id < end; id += step) ids.push_back(id);
  return ids;
}

// Every record of `path` equals the synthetic one where `expected_done`, and reads as
// pending with no trajectory or stress elsewhere.
void expect_dataset(const std::filesystem::path& path, const DatasetPlan& plan,
                    const std::vector<std::uint8_t>& expected_done) {
  const DatasetReader reader(path);
  const DatasetLayout& layout = reader.layout();
  ASSERT_EQ(layout.candidate_count, plan.candidates.size());
  EXPECT_EQ(reader.done(), expected_done);
  const std::vector<CandidateRecord> records = reader.candidates();
  for (std::uint64_t id = 0; id < layout.candidate_count; ++id) {
    if (!expected_done[id]) {
      EXPECT_EQ(records[id].status, Status::kPending) << "candidate " << id;
      EXPECT_FALSE(reader.trajectory(id)) << "candidate " << id;
      continue;
    }
    const CandidateResult expected = synthetic_result(layout, id, kSeed);
    EXPECT_EQ(records[id], expected.record) << "candidate " << id;
    EXPECT_EQ(reader.trajectory(id), expected.trajectory) << "candidate " << id;
    EXPECT_EQ(reader.stress(id), expected.stress) << "candidate " << id;
    EXPECT_EQ(reader.finger_stress(id), expected.finger_stress) << "candidate " << id;
  }
}

TEST(DatasetWriter, CollectiveWriteReadsBackExactly) {
  const auto folder = testing::shared_scratch(MPI_COMM_WORLD, "readback");
  const auto path = folder / "data.h5";
  const DatasetPlan plan = synthetic_plan(30);
  const Provenance provenance = synthetic_provenance(kJob, kSeed);
  {
    DatasetWriter writer = DatasetWriter::create(path, plan, provenance, MPI_COMM_WORLD);
    // Uneven batches, one where rank 0 has nothing; 28 and 29 stay pending.
    write_batches(
        writer, {{{0, 1, 2, 5}, {3, 4}}, {{}, range(6, 12)}, {range(12, 28, 2), range(13, 28, 2)}});
    EXPECT_EQ(writer.pending(), (std::vector<std::uint64_t>{28, 29}));
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (world_rank() != 0) return;

  std::vector<std::uint8_t> done(30, 1);
  done[28] = done[29] = 0;
  expect_dataset(path, plan, done);

  const DatasetReader reader(path);
  const Provenance read = reader.provenance();
  EXPECT_EQ(read.job_text, provenance.job_text);
  EXPECT_EQ(read.job_file, provenance.job_file);
  EXPECT_EQ(read.seed, provenance.seed);
  EXPECT_EQ(read.grip_version, provenance.grip_version);
  EXPECT_EQ(read.git_revision, provenance.git_revision);
  ASSERT_EQ(read.parameters.size(), provenance.parameters.size());
  for (std::size_t i = 0; i < read.parameters.size(); ++i) {
    EXPECT_EQ(read.parameters[i].key, provenance.parameters[i].key);
    EXPECT_EQ(read.parameters[i].value, provenance.parameters[i].value);
  }
  EXPECT_EQ(reader.job_id(), job_id(kJob, kSeed));
  for (std::uint32_t o = 0; o < plan.objects.size(); ++o) {
    const ObjectRecord object = reader.object(o);
    const ObjectRecord& want = plan.objects[o];
    EXPECT_EQ(object.name, want.name);
    EXPECT_EQ(object.category, want.category);
    EXPECT_EQ(object.scale, want.scale);
    EXPECT_EQ(object.soft, want.soft);
    EXPECT_EQ(object.material.young_modulus, want.material.young_modulus);
    EXPECT_EQ(object.material.friction, want.material.friction);
    EXPECT_EQ(object.vertices, want.vertices);
    EXPECT_EQ(object.triangles, want.triangles);
    EXPECT_EQ(object.tets, want.tets);
  }
  for (std::uint32_t g = 0; g < plan.grippers.size(); ++g) {
    const GripperRecord gripper = reader.gripper(g);
    const GripperRecord& want = plan.grippers[g];
    EXPECT_EQ(gripper.name, want.name);
    EXPECT_EQ(gripper.kind, want.kind);
    EXPECT_EQ(gripper.hands, want.hands);
    EXPECT_EQ(gripper.joint_names, want.joint_names);
    EXPECT_EQ(gripper.finger_names, want.finger_names);
    EXPECT_EQ(gripper.vertices, want.vertices);
    EXPECT_EQ(gripper.triangles, want.triangles);
  }
  for (std::uint64_t id = 0; id < plan.candidates.size(); ++id) {
    EXPECT_EQ(reader.layout().object[id], plan.candidates[id].object);
    EXPECT_EQ(reader.layout().gripper[id], plan.candidates[id].gripper);
  }
}

TEST(DatasetWriter, BytesDoNotDependOnWhichRankWroteARecord) {
  const auto folder = testing::shared_scratch(MPI_COMM_WORLD, "ranks");
  const DatasetPlan plan = synthetic_plan(24);
  const Provenance provenance = synthetic_provenance(kJob, kSeed);
  {
    DatasetWriter writer = DatasetWriter::create(folder / "a.h5", plan, provenance, MPI_COMM_WORLD);
    write_batches(writer, {{range(0, 24, 2), range(1, 24, 2)}});
  }
  {
    DatasetWriter writer = DatasetWriter::create(folder / "b.h5", plan, provenance, MPI_COMM_WORLD);
    write_batches(writer, {{range(12, 24), range(0, 5)}, {{}, range(5, 12)}});
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (world_rank() == 0) {
    const std::string a = file_bytes(folder / "a.h5");
    EXPECT_FALSE(a.empty());
    EXPECT_TRUE(a == file_bytes(folder / "b.h5"));
  }
}

// Work units committed by each rank alone, in an order unlike the ids', give the bytes of one
// collective write; the journal lists every id once; a bad unit is refused on its rank only.
TEST(DatasetWriter, UnitCommitsGiveTheBytesOfACollectiveWrite) {
  const auto folder = testing::shared_scratch(MPI_COMM_WORLD, "units");
  const DatasetPlan plan = synthetic_plan(24);
  const Provenance provenance = synthetic_provenance(kJob, kSeed);
  {
    DatasetWriter writer = DatasetWriter::create(folder / "a.h5", plan, provenance, MPI_COMM_WORLD);
    write_batches(writer, {{range(0, 12), range(12, 24)}});
  }
  {
    DatasetWriter writer = DatasetWriter::create(folder / "u.h5", plan, provenance, MPI_COMM_WORLD);
    const std::vector<std::vector<std::uint64_t>> units =
        world_rank() == 0 ? std::vector<std::vector<std::uint64_t>>{range(20, 24), range(2, 6), {0}}
                          : std::vector<std::vector<std::uint64_t>>{range(6, 20), {1}};
    if (world_rank() == 1) {  // a joint missing: refused here alone, nothing written
      std::vector<CandidateResult> bad = results_for(writer.layout(), {1});
      bad[0].record.joints.pop_back();
      EXPECT_THROW(writer.commit_unit(bad), DatasetError);
      EXPECT_FALSE(writer.is_done(1));
    }
    for (const std::vector<std::uint64_t>& unit : units) {
      writer.commit_unit(results_for(writer.layout(), unit));
      writer.poll_journal();
    }
    EXPECT_THROW(writer.commit_unit(results_for(writer.layout(), {units[0][0]})), DatasetError);
    writer.end_units([] {});
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (world_rank() == 0) {
    EXPECT_TRUE(file_bytes(folder / "a.h5") == file_bytes(folder / "u.h5"));
    std::vector<std::uint64_t> done = Journal::read(Journal::path_for(folder / "u.h5")).done;
    std::sort(done.begin(), done.end());
    EXPECT_EQ(done, range(0, 24));
  }
  DatasetWriter resumed = DatasetWriter::resume(folder / "u.h5", provenance, MPI_COMM_WORLD);
  EXPECT_TRUE(resumed.pending().empty());
}

TEST(DatasetWriter, RefusesBadBatchesOnEveryRankAndWritesARecordOnce) {
  const auto folder = testing::shared_scratch(MPI_COMM_WORLD, "bad");
  const auto path = folder / "data.h5";
  const DatasetPlan plan = synthetic_plan(12);
  DatasetWriter writer =
      DatasetWriter::create(path, plan, synthetic_provenance(kJob, kSeed), MPI_COMM_WORLD);
  // Rank 1 hands over a record with a joint missing: every rank throws.
  std::vector<CandidateResult> results =
      results_for(writer.layout(), {world_rank() == 0 ? 0u : 1u});
  if (world_rank() == 1) results[0].record.joints.pop_back();
  EXPECT_THROW(writer.write(results), DatasetError);
  // Both ranks hand over candidate 3.
  EXPECT_THROW(writer.write(results_for(writer.layout(), {3})), DatasetError);
  EXPECT_EQ(writer.pending().size(), 12u);
  // A record is written once.
  writer.write(results_for(writer.layout(), world_rank() == 0 ? std::vector<std::uint64_t>{3}
                                                              : std::vector<std::uint64_t>{}));
  EXPECT_THROW(
      writer.write(results_for(writer.layout(), world_rank() == 1 ? std::vector<std::uint64_t>{3}
                                                                  : std::vector<std::uint64_t>{})),
      DatasetError);
  EXPECT_EQ(writer.pending().size(), 11u);
  EXPECT_TRUE(writer.is_done(3));
}

TEST(DatasetWriter, ResumeSkipsCommittedCandidatesAndFinishesTheSet) {
  const auto folder = testing::shared_scratch(MPI_COMM_WORLD, "resume");
  const auto path = folder / "data.h5";
  const DatasetPlan plan = synthetic_plan(20);
  const Provenance provenance = synthetic_provenance(kJob, kSeed);
  {
    DatasetWriter writer = DatasetWriter::create(path, plan, provenance, MPI_COMM_WORLD);
    write_batches(writer, {{{0, 2, 4}, {7, 9}}});
  }
  {
    DatasetWriter writer = DatasetWriter::resume(path, provenance, MPI_COMM_WORLD);
    std::vector<std::uint64_t> want = range(0, 20);
    std::erase_if(
        want, [](std::uint64_t id) { return id == 0 || id == 2 || id == 4 || id == 7 || id == 9; });
    ASSERT_EQ(writer.pending(), want);
    std::vector<std::uint64_t> mine;
    for (std::size_t i = 0; i < want.size(); ++i) {
      if (static_cast<int>(i % 2) == world_rank()) mine.push_back(want[i]);
    }
    writer.write(results_for(writer.layout(), mine));
    EXPECT_TRUE(writer.pending().empty());
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (world_rank() == 0) expect_dataset(path, plan, std::vector<std::uint8_t>(20, 1));
}

// A kill after a batch's done flags were flushed but before its journal line was complete:
// the file says done, the journal does not, so the batch is redone and journaled once.
TEST(DatasetWriter, ResumeRedoesCandidatesFlaggedButNotJournaled) {
  const auto folder = testing::shared_scratch(MPI_COMM_WORLD, "unjournaled");
  const auto path = folder / "data.h5";
  const auto journal = Journal::path_for(path);
  const DatasetPlan plan = synthetic_plan(8);
  const Provenance provenance = synthetic_provenance(kJob, kSeed);
  std::uintmax_t first_batch_end = 0;
  {
    DatasetWriter writer = DatasetWriter::create(path, plan, provenance, MPI_COMM_WORLD);
    write_batches(writer, {{{0}, {1}}});
    if (world_rank() == 0) first_batch_end = std::filesystem::file_size(journal);
    write_batches(writer, {{{2, 3}, {4}}});
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (world_rank() == 0) {
    // Cut the second batch's line to a torn fragment, as a crash mid-append leaves it.
    std::filesystem::resize_file(journal, first_batch_end + 6);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  {
    DatasetWriter writer = DatasetWriter::resume(path, provenance, MPI_COMM_WORLD);
    EXPECT_EQ(writer.pending(), (std::vector<std::uint64_t>{2, 3, 4, 5, 6, 7}));
    write_batches(writer, {{{2, 4, 6}, {3, 5, 7}}});
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (world_rank() != 0) return;
  EXPECT_EQ(Journal::read(journal).done, (std::vector<std::uint64_t>{0, 1, 2, 3, 4, 5, 6, 7}));
  expect_dataset(path, plan, std::vector<std::uint8_t>(8, 1));
}

// Runs a resume that must fail on every rank, with `message` in its error, and checks that
// neither the dataset nor its journal changed by a byte.
void expect_refused(const std::filesystem::path& path, const Provenance& provenance,
                    const std::string& message) {
  MPI_Barrier(MPI_COMM_WORLD);  // rank 0 has finished preparing the file
  const auto journal = Journal::path_for(path);
  const std::string before = file_bytes(path);
  const bool had_journal = std::filesystem::exists(journal);
  const std::string journal_before = had_journal ? file_bytes(journal) : "";
  MPI_Barrier(MPI_COMM_WORLD);
  try {
    DatasetWriter::resume(path, provenance, MPI_COMM_WORLD);
    ADD_FAILURE() << "resume of " << path << " was not refused";
  } catch (const DatasetError& e) {
    EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
  MPI_Barrier(MPI_COMM_WORLD);
  EXPECT_TRUE(file_bytes(path) == before);
  EXPECT_EQ(std::filesystem::exists(journal), had_journal);
  if (had_journal) {
    EXPECT_TRUE(file_bytes(journal) == journal_before);
  }
}

void make_partial_dataset(const std::filesystem::path& path) {
  DatasetWriter writer = DatasetWriter::create(path, synthetic_plan(10),
                                               synthetic_provenance(kJob, kSeed), MPI_COMM_WORLD);
  write_batches(writer, {{{0, 1}, {2}}});
}

TEST(DatasetWriter, RefusesToResumeAnotherJobsDataset) {
  const auto folder = testing::shared_scratch(MPI_COMM_WORLD, "other_job");
  const auto path = folder / "data.h5";
  make_partial_dataset(path);
  expect_refused(path, synthetic_provenance(kJob + "# edited\n", kSeed), "another job");
  expect_refused(path, synthetic_provenance(kJob, kSeed + 1), "another job");
}

// Same job and seed but another plan (a grip that meshed an object otherwise): the resumed
// writer refuses it on every rank and the dataset and journal keep every byte.
TEST(DatasetWriter, ResumedWriterRefusesAnotherPlan) {
  const auto folder = testing::shared_scratch(MPI_COMM_WORLD, "other_plan");
  const auto path = folder / "data.h5";
  make_partial_dataset(path);
  MPI_Barrier(MPI_COMM_WORLD);
  const std::string before = file_bytes(path);
  const std::string journal_before = file_bytes(Journal::path_for(path));
  const Provenance provenance = synthetic_provenance(kJob, kSeed);
  DatasetPlan moved_vertex = synthetic_plan(10);
  moved_vertex.objects[0].vertices[4] += 1e-9;
  DatasetPlan moved_finger = synthetic_plan(10);
  moved_finger.grippers[0].vertices[0] += 1e-9;
  DatasetPlan other_slots = synthetic_plan(10);
  other_slots.candidates[3].frames = !other_slots.candidates[3].frames;
  const std::vector<std::pair<const DatasetPlan*, std::string>> refusals = {
      {&moved_vertex, "object '" + moved_vertex.objects[0].name + "' (/objects/000000/vertices)"},
      {&moved_finger, "gripper '" + moved_finger.grippers[0].name + "' (/grippers/000/vertices)"},
      {&other_slots, "other candidates (10, their slots in /candidates/frame_slot)"}};
  {
    DatasetWriter writer = DatasetWriter::resume(path, provenance, MPI_COMM_WORLD);
    writer.check_plan(synthetic_plan(10));  // the plan it was made with
    for (const auto& [plan, message] : refusals) {
      try {
        writer.check_plan(*plan);
        ADD_FAILURE() << "not refused: " << message;
      } catch (const DatasetError& e) {
        EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
      }
    }
  }
  MPI_Barrier(MPI_COMM_WORLD);
  EXPECT_TRUE(file_bytes(path) == before);
  EXPECT_TRUE(file_bytes(Journal::path_for(path)) == journal_before);
}

TEST(DatasetWriter, RefusesToResumeATruncatedDataset) {
  const auto folder = testing::shared_scratch(MPI_COMM_WORLD, "truncated");
  const auto path = folder / "data.h5";
  make_partial_dataset(path);
  if (world_rank() == 0) {
    const std::string bytes = file_bytes(path);
    testing::write_bytes(path, bytes.substr(0, bytes.size() / 2));
  }
  expect_refused(path, synthetic_provenance(kJob, kSeed), "truncated");
}

TEST(DatasetWriter, RefusesToResumeAFileThatIsNotHdf5) {
  const auto folder = testing::shared_scratch(MPI_COMM_WORLD, "not_hdf5");
  const auto path = folder / "data.h5";
  if (world_rank() == 0) testing::write_bytes(path, "id,label\n1,cup\n");
  expect_refused(path, synthetic_provenance(kJob, kSeed), "not an HDF5 file");
}

TEST(DatasetWriter, RefusesToResumeADatasetWithoutItsJournal) {
  const auto folder = testing::shared_scratch(MPI_COMM_WORLD, "no_journal");
  const auto path = folder / "data.h5";
  make_partial_dataset(path);
  if (world_rank() == 0) std::filesystem::remove(Journal::path_for(path));
  expect_refused(path, synthetic_provenance(kJob, kSeed), "journal is missing");
}

TEST(DatasetWriter, CreateRefusesAnExistingFile) {
  const auto folder = testing::shared_scratch(MPI_COMM_WORLD, "exists");
  const auto path = folder / "data.h5";
  if (world_rank() == 0) testing::write_bytes(path, "precious");
  MPI_Barrier(MPI_COMM_WORLD);
  EXPECT_THROW(DatasetWriter::create(path, synthetic_plan(4), synthetic_provenance(kJob, kSeed),
                                     MPI_COMM_WORLD),
               DatasetError);
  EXPECT_EQ(file_bytes(path), "precious");
}

}  // namespace
}  // namespace grip::io
