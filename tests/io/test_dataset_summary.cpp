// The summary `grip inspect` prints, against counts and statistics computed here directly
// from the synthetic results that were written.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "io/dataset_summary.hpp"
#include "io/dataset_writer.hpp"
#include "tests/io/io_test_files.hpp"
#include "tests/io/synthetic_dataset.hpp"

namespace grip::io {
namespace {

TEST(Statistics, MeanMinMedianMaxOfFiniteValues) {
  const Statistics odd = statistics({3, 1, NAN, 2});
  EXPECT_EQ(odd.count, 3u);
  EXPECT_DOUBLE_EQ(odd.mean, 2.0);
  EXPECT_EQ(odd.min, 1.0);
  EXPECT_EQ(odd.median, 2.0);
  EXPECT_EQ(odd.max, 3.0);
  EXPECT_EQ(statistics({4, 1, 3, 2}).median, 2.5);
  EXPECT_EQ(statistics({}).count, 0u);
}

TEST(DatasetSummary, CountsCommittedCandidatesOnly) {
  const auto folder = testing::shared_scratch(MPI_COMM_WORLD, "summary");
  const auto path = folder / "data.h5";
  constexpr std::uint64_t kSeed = 3;
  constexpr std::uint64_t kCount = 24;
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const DatasetPlan plan = testing::synthetic_plan(kCount);
  std::vector<std::uint64_t> written;  // all but every fourth candidate
  {
    DatasetWriter writer = DatasetWriter::create(
        path, plan, testing::synthetic_provenance("[job]\n", kSeed), MPI_COMM_WORLD);
    std::vector<CandidateResult> mine;
    for (std::uint64_t id = 0; id < kCount; ++id) {
      if (id % 4 == 3) continue;
      written.push_back(id);
      if (static_cast<int>(id % 2) == rank) {
        mine.push_back(testing::synthetic_result(writer.layout(), id, kSeed));
      }
    }
    writer.write(mine);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank != 0) return;

  const DatasetReader reader(path);
  const DatasetSummary summary = summarize(reader);
  EXPECT_EQ(summary.candidates, kCount);
  EXPECT_EQ(summary.done, written.size());
  std::uint64_t success = 0;
  std::vector<std::uint64_t> gripper_success(plan.grippers.size(), 0);
  std::vector<std::uint64_t> object_done(plan.objects.size(), 0);
  std::array<std::uint64_t, kFailureKindCount> failures{};
  double d2_sum = 0;
  double d2_max = 0;
  std::vector<double> peak_object, peak_finger;  // per successful candidate with that stress
  for (const std::uint64_t id : written) {
    const CandidateResult result = testing::synthetic_result(reader.layout(), id, kSeed);
    const CandidateRecord& r = result.record;
    ++object_done[plan.candidates[id].object];
    if (r.status == Status::kSuccess) {
      ++success;
      ++gripper_success[plan.candidates[id].gripper];
      d2_sum += r.d2;
      d2_max = std::max(d2_max, r.d2);
      if (result.stress) {
        peak_object.push_back(*std::max_element(result.stress->begin(), result.stress->end()));
      }
      if (result.finger_stress) {
        peak_finger.push_back(
            *std::max_element(result.finger_stress->begin(), result.finger_stress->end()));
      }
    } else {
      ++failures[static_cast<std::size_t>(r.failure)];
    }
  }
  ASSERT_GT(success, 0u);
  ASSERT_LT(success, written.size());
  EXPECT_EQ(summary.success, success);
  for (std::size_t g = 0; g < plan.grippers.size(); ++g) {
    EXPECT_EQ(summary.by_gripper[g].name, plan.grippers[g].name);
    EXPECT_EQ(summary.by_gripper[g].success, gripper_success[g]);
  }
  for (std::size_t o = 0; o < plan.objects.size(); ++o) {
    EXPECT_EQ(summary.by_object[o].candidates, kCount / plan.objects.size());
    EXPECT_EQ(summary.by_object[o].done, object_done[o]);
  }
  EXPECT_EQ(summary.failures, failures);
  EXPECT_EQ(summary.d2.count, success);
  EXPECT_NEAR(summary.d2.mean, d2_sum / static_cast<double>(success), 1e-15);
  EXPECT_EQ(summary.d2.max, d2_max);
  EXPECT_EQ(summary.d1.max, 0.0);  // the synthetic successes never penetrate
  ASSERT_FALSE(peak_object.empty());
  ASSERT_FALSE(peak_finger.empty());
  EXPECT_EQ(summary.peak_object_stress.count, peak_object.size());
  EXPECT_EQ(summary.peak_object_stress.max,
            *std::max_element(peak_object.begin(), peak_object.end()));
  EXPECT_EQ(summary.peak_finger_stress.count, peak_finger.size());
  EXPECT_EQ(summary.peak_finger_stress.min,
            *std::min_element(peak_finger.begin(), peak_finger.end()));
}

}  // namespace
}  // namespace grip::io
