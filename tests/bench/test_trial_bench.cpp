// `grip bench trial` on a tiny plan (rigid jaws on one box, 2 candidates, 2 repeats): the
// schedule interleaves the arms' candidates repeat by repeat and ends with the reference round,
// bad options are refused in one message naming the command, and every run has CPU time, steps
// and stage seconds that fit in its wall time, in the tables, the CSV and the JSON line. No
// figure is asserted beyond that.
#include "bench/trial/trial_benchmark.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "bench/trial/trial_report.hpp"

namespace grip::bench {
namespace {

TEST(TrialBench, ScheduleInterleavesArmsRepeatByRepeatThenTheReference) {
  // Arm 0 has 2 candidates, arm 1 one: index 1 is arm 0's alone.
  const std::vector<TrialBenchSlot> slots = trial_bench_schedule({2, 1}, 2, true);
  const std::vector<std::tuple<std::size_t, std::size_t, int, bool>> expected = {
      {0, 0, 1, false}, {1, 0, 1, false}, {0, 1, 1, false},  // repeat 1
      {0, 0, 2, false}, {1, 0, 2, false}, {0, 1, 2, false},  // repeat 2
      {0, 0, 1, true},  {1, 0, 1, true},  {0, 1, 1, true}};  // the reference
  ASSERT_EQ(slots.size(), expected.size());
  for (std::size_t i = 0; i < slots.size(); ++i) {
    EXPECT_EQ(
        std::make_tuple(slots[i].arm, slots[i].candidate, slots[i].repeat, slots[i].reference),
        expected[i])
        << "slot " << i;
  }
  EXPECT_EQ(trial_bench_schedule({2, 1}, 1, false).size(), 3u);
}

TEST(TrialBench, RefusesBadOptionsNamingTheCommand) {
  const auto message = [](const TrialBenchOptions& options) {
    try {
      check_trial_bench_options(options);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  TrialBenchOptions options;
  options.repeats = 0;
  EXPECT_EQ(message(options), "grip bench trial: --repeats must be at least 1");
  options.repeats = 1;
  options.candidates = -1;
  EXPECT_EQ(message(options), "grip bench trial: --candidates must not be negative");
  options.candidates = 0;
  options.arms = {{"gripper-x", false}};
  EXPECT_EQ(message(options).rfind("grip bench trial: unknown gripper 'gripper-x'", 0), 0u)
      << message(options);
  options.arms = {{"leap", true}};
  options.categories = {"teacup"};
  EXPECT_NE(message(options).find("teacup"), std::string::npos) << message(options);
  options.categories = {};
  EXPECT_EQ(message(options), "accepted");
}

TEST(TrialBench, DefaultCandidatesAreFewWhereTrialsAreDear) {
  EXPECT_EQ(trial_bench_candidates({"parallel-jaw", false}), 8);
  EXPECT_EQ(trial_bench_candidates({"leap", false}), 4);
  EXPECT_EQ(trial_bench_candidates({"fin-ray", false}), 2);
  EXPECT_EQ(trial_bench_candidates({"fin-ray", true}), 2);
  EXPECT_EQ(trial_bench_candidates({"leap", true}), 2);
}

std::vector<std::string> fields(const std::string& row) {
  std::vector<std::string> out;
  std::stringstream in(row);
  for (std::string f; std::getline(in, f, ',');) out.push_back(f);
  return out;
}

TEST(TrialBench, RigidJawsOnABoxTimeEveryRunAndReportIt) {
  TrialBenchOptions options;
  options.arms = {{"parallel-jaw", false}};
  options.categories = {"box"};
  options.candidates = 2;
  options.repeats = 2;
  options.out = std::filesystem::path(::testing::TempDir()) / "bench_trial";
  const TrialBenchResult result = run_trial_bench(options);
  ASSERT_EQ(result.arms.size(), 1u);
  ASSERT_EQ(result.arms.front().candidates.size(), 2u);
  ASSERT_EQ(result.runs.size(), 6u);  // 2 candidates x (2 repeats + the reference)
  for (const TrialBenchRun& run : result.runs) {
    EXPECT_GT(run.cpu_seconds, 0.0);
    EXPECT_GT(run.trial.newton.steps, 0u);
    EXPECT_GT(run.trial.newton.iterations, 0u);
    EXPECT_GT(run.stages.total(), 0.0);
    EXPECT_LE(run.stages.total(), run.wall_seconds);
    double summed = 0.0;
    for (const double s : stage_seconds(run)) summed += s;
    EXPECT_NEAR(summed, run.wall_seconds, 1e-9);
  }

  const std::vector<TrialBenchSummary> summaries = trial_bench_summaries(result);
  ASSERT_EQ(summaries.size(), 1u);
  const TrialBenchSummary& s = summaries.front();
  EXPECT_EQ(s.arm, "parallel-jaw x rigid");
  EXPECT_EQ(s.candidates, 2);
  EXPECT_EQ(s.runs, 4);
  EXPECT_EQ(s.compared, 2);
  EXPECT_TRUE(s.repeats_agree) << "a trial's answer changed between repeats";
  EXPECT_GT(s.cpu_seconds, 0.0);

  std::ostringstream table;
  write_trial_bench_tables(table, summaries);
  EXPECT_NE(table.str().find("| parallel-jaw x rigid | 2 | 4 |"), std::string::npos) << table.str();
  EXPECT_NE(table.str().find("protocol and other"), std::string::npos);

  std::ostringstream line;
  write_trial_bench_json_line(line, result, summaries);
  EXPECT_EQ(line.str().find('\n'), line.str().size() - 1) << "one line";
  const nlohmann::json json = nlohmann::json::parse(line.str());
  EXPECT_EQ(json["benchmark"], "trial");
  EXPECT_EQ(json["repeats"], 2);
  EXPECT_EQ(json["arms"][0]["candidates"], 2);
  EXPECT_EQ(json["arms"][0]["compared"], 2);
  EXPECT_EQ(json["arms"][0]["stage_seconds"].size(), kTrialBenchStages.size());

  write_trial_bench_files(options.out, result, summaries);
  EXPECT_TRUE(std::filesystem::exists(options.out / "trial.md"));
  std::ifstream csv(options.out / "trial.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header.rfind("arm,category,seed,candidate,settings,repeat,cpu_s,", 0), 0u) << header;
  // Repeat 1 of both candidates, repeat 2 of both, then the reference.
  const std::vector<std::tuple<std::string, std::string, std::string>> order = {
      {"0", "defaults", "1"}, {"1", "defaults", "1"},  {"0", "defaults", "2"},
      {"1", "defaults", "2"}, {"0", "reference", "1"}, {"1", "reference", "1"}};
  std::size_t rows = 0;
  for (std::string row; std::getline(csv, row); ++rows) {
    const std::vector<std::string> f = fields(row);
    ASSERT_EQ(f.size(), fields(header).size()) << row;
    ASSERT_LT(rows, order.size());
    EXPECT_EQ(std::make_tuple(f[3], f[4], f[5]), order[rows]) << row;
    EXPECT_GT(std::stod(f[6]), 0.0) << row;  // cpu_s
    EXPECT_GT(std::stol(f[9]), 0) << row;    // steps
  }
  EXPECT_EQ(rows, order.size());
}

}  // namespace
}  // namespace grip::bench
