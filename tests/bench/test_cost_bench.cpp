// `grip bench cost`: the statistics are nearest-rank ones on a known list, split by arm and
// verdict; the failing trials' stage shares sum to 1; figures in reference units are CPU seconds
// over the reference's; and a small run (rigid jaws, one box, 2 candidates) writes one CSV row
// per candidate whose CPU time is positive, whose stages fit in it and whose ratio is its CPU
// seconds over the run's reference.
#include "bench/cost/cost_benchmark.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "bench/cost/cost_report.hpp"
#include "bench/cost/cost_statistics.hpp"

namespace grip::bench {
namespace {

TEST(CostBench, StatisticsOfAKnownList) {
  const CostStatistics s = cost_statistics({5, 1, 4, 2, 3, 10, 6, 7, 8, 9});
  EXPECT_EQ(s.n, 10);
  EXPECT_DOUBLE_EQ(s.mean, 5.5);
  EXPECT_EQ(s.median, 5.0);  // rank ceil(0.5 x 10) = 5: the lower middle value
  EXPECT_EQ(s.p90, 9.0);     // rank 9
  EXPECT_EQ(s.max, 10.0);
  const CostStatistics odd = cost_statistics({3, 1, 2});
  EXPECT_EQ(odd.median, 2.0);  // rank 2
  EXPECT_EQ(odd.p90, 3.0);     // rank ceil(2.7) = 3
  EXPECT_EQ(cost_statistics({0.25}).p90, 0.25);
  const CostStatistics none = cost_statistics({});
  EXPECT_EQ(none.n, 0);
  EXPECT_TRUE(std::isnan(none.mean) && std::isnan(none.median) && std::isnan(none.max));
}

CostRun run_of(const std::string& arm, io::FailureKind failure, double cpu) {
  CostRun run;
  run.arm = arm;
  run.trial.failure = failure;
  run.trial.status =
      failure == io::FailureKind::kNone ? io::Status::kSuccess : io::Status::kFailure;
  run.cpu_seconds = cpu;
  run.wall_seconds = cpu;  // alone on its thread
  return run;
}

// Two arms: the jaws with 2 held and 2 failing trials of two kinds, the hand with 1 held.
CostResult known_result() {
  CostResult result;
  result.arms = {"parallel-jaw x rigid", "leap x rigid"};
  result.runs = {run_of("parallel-jaw x rigid", io::FailureKind::kNone, 0.2),
                 run_of("parallel-jaw x rigid", io::FailureKind::kDisplaced, 4.0),
                 run_of("parallel-jaw x rigid", io::FailureKind::kNone, 0.4),
                 run_of("parallel-jaw x rigid", io::FailureKind::kLostContact, 6.0),
                 run_of("leap x rigid", io::FailureKind::kNone, 1.0)};
  result.reference.start = {0.02, 0.04};
  result.reference.end = {0.03};
  return result;
}

TEST(CostBench, RowsSplitByArmAndVerdict) {
  const CostResult result = known_result();
  EXPECT_DOUBLE_EQ(result.reference.seconds(), 0.03);  // rank 2 of 0.02, 0.03, 0.04
  EXPECT_DOUBLE_EQ(result.reference.start_median(), 0.02);
  EXPECT_DOUBLE_EQ(result.reference.end_median(), 0.03);
  const std::vector<CostRow> rows = cost_rows(result);
  std::vector<std::string> order;
  for (const CostRow& row : rows) order.push_back(row.arm + ": " + row.verdicts);
  // io::FailureKind's order: lost_contact (3) before displaced (4); the hand has no failures.
  EXPECT_EQ(order,
            (std::vector<std::string>{
                "parallel-jaw x rigid: all", "parallel-jaw x rigid: success",
                "parallel-jaw x rigid: failure", "parallel-jaw x rigid: lost_contact",
                "parallel-jaw x rigid: displaced", "leap x rigid: all", "leap x rigid: success"}));
  ASSERT_EQ(rows.size(), order.size());
  const CostStatistics& all = rows[0].cpu;
  EXPECT_EQ(all.n, 4);
  EXPECT_DOUBLE_EQ(all.mean, 2.65);
  EXPECT_EQ(all.median, 0.4);
  EXPECT_EQ(all.p90, 6.0);
  const CostStatistics& success = rows[1].cpu;
  EXPECT_EQ(success.n, 2);
  EXPECT_DOUBLE_EQ(success.mean, 0.3);
  EXPECT_EQ(success.max, 0.4);
  const CostStatistics& failure = rows[2].cpu;
  EXPECT_EQ(failure.n, 2);
  EXPECT_EQ(failure.median, 4.0);
  EXPECT_EQ(rows[3].cpu.max, 6.0);   // lost_contact
  EXPECT_EQ(rows[4].cpu.n, 1);       // displaced
  EXPECT_EQ(rows[5].cpu.mean, 1.0);  // the hand's all
}

TEST(CostBench, ReferenceUnitsAreCpuSecondsOverTheReference) {
  const CostStatistics seconds = cost_statistics({0.1, 0.3, 0.9});
  const CostStatistics units = in_reference_units(seconds, 0.05);
  EXPECT_EQ(units.n, 3);
  EXPECT_DOUBLE_EQ(units.mean, seconds.mean / 0.05);
  EXPECT_DOUBLE_EQ(units.median, 6.0);
  EXPECT_DOUBLE_EQ(units.p90, 18.0);
  EXPECT_DOUBLE_EQ(units.max, 18.0);
  // The rows' reference units are their CPU figures over the run's reference.
  for (const CostRow& row : cost_rows(known_result())) {
    EXPECT_DOUBLE_EQ(row.reference.mean, row.cpu.mean / 0.03) << row.arm << " " << row.verdicts;
    EXPECT_DOUBLE_EQ(row.reference.max, row.cpu.max / 0.03) << row.arm << " " << row.verdicts;
  }
}

TEST(CostBench, FailingStageSharesSumToOne) {
  CostResult result = known_result();
  result.runs[1].stages.factorization = 1.0;  // displaced: 4 CPU s
  result.runs[1].stages.solve = 1.0;
  result.runs[3].stages.factorization = 3.0;  // lost_contact: 6 CPU s
  result.runs[3].stages.broad_phase = 2.0;
  result.runs[0].stages.derivatives = 0.1;  // held: not among the failing
  const std::vector<const CostRun*> failing = failing_runs(result, "parallel-jaw x rigid");
  ASSERT_EQ(failing.size(), 2u);
  const auto shares = stage_shares(failing);
  double sum = 0.0;
  for (const double share : shares) sum += share;
  EXPECT_NEAR(sum, 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(shares[3], 0.4);      // factorization: 4 of 10 CPU s
  EXPECT_DOUBLE_EQ(shares[0], 0.2);      // broad phase
  EXPECT_DOUBLE_EQ(shares[4], 0.1);      // solve
  EXPECT_DOUBLE_EQ(shares.back(), 0.3);  // protocol: what the stages leave
  EXPECT_EQ(shares[1], 0.0);             // the held trial's derivatives are not here
  EXPECT_TRUE(std::isnan(stage_shares(failing_runs(result, "leap x rigid"))[0]));
}

TEST(CostBench, PlanRefusesBadOptions) {
  CostOptions options;
  EXPECT_EQ(plan_cost(options).size(), 12u);  // 3 grippers x 4 categories, rigid only
  options.soft = true;
  options.grippers = {"leap"};
  EXPECT_EQ(plan_cost(options).size(), 8u);
  CostOptions bad;
  bad.grippers = {"claw"};
  EXPECT_THROW(plan_cost(bad), std::invalid_argument);
  bad = {};
  bad.reference_repeats = 0;
  EXPECT_THROW(plan_cost(bad), std::invalid_argument);
  bad = {};
  bad.candidates = 0;
  EXPECT_THROW(plan_cost(bad), std::invalid_argument);
}

std::vector<std::string> fields(const std::string& row) {
  std::vector<std::string> out;
  std::stringstream in(row);
  for (std::string f; std::getline(in, f, ',');) out.push_back(f);
  return out;
}

TEST(CostBench, SmallRunWritesOneRowPerCandidate) {
  CostOptions options;
  options.grippers = {"parallel-jaw"};
  options.categories = {"box"};
  options.candidates = 2;
  options.reference_repeats = 1;
  options.out = std::filesystem::path(::testing::TempDir()) / "cost";
  const CostResult result = run_cost(options);
  ASSERT_EQ(result.runs.size(), 2u) << "the box's first shape got fewer candidates";
  ASSERT_EQ(result.reference.start.size(), 1u);
  ASSERT_EQ(result.reference.end.size(), 1u);
  const double reference = result.reference.seconds();
  EXPECT_GT(reference, 0.0);
  EXPECT_GT(result.reference.flops, 0.0);
  const std::vector<CostRow> rows = cost_rows(result);
  write_cost_files(options.out, result, rows);

  std::ifstream csv(options.out / "cost.csv");
  std::string line;
  ASSERT_TRUE(std::getline(csv, line));
  const std::vector<std::string> head = fields(line);
  std::map<std::string, std::size_t> column;
  for (std::size_t i = 0; i < head.size(); ++i) column[head[i]] = i;
  for (const char* name : {"arm", "verdict", "cpu_s", "cpu_reference_units", "steps",
                           "newton_iterations", "factorization", "protocol", "setup_cpu_s"}) {
    EXPECT_TRUE(column.contains(name)) << name;
  }
  int candidates = 0;
  while (std::getline(csv, line)) {
    const std::vector<std::string> f = fields(line);
    ASSERT_EQ(f.size(), head.size()) << line;
    ++candidates;
    EXPECT_EQ(f[column["arm"]], "parallel-jaw x rigid");
    const double cpu = std::stod(f[column["cpu_s"]]);
    EXPECT_GT(cpu, 0.0) << line;
    EXPECT_GT(std::stol(f[column["steps"]]), 0) << line;
    // The protocol is the trial's wall time less the stages' (wall s on the same thread).
    EXPECT_GE(std::stod(f[column["protocol"]]), -1e-6) << line;
    EXPECT_NEAR(std::stod(f[column["cpu_reference_units"]]), cpu / reference,
                1e-7 * cpu / reference)
        << line;
  }
  EXPECT_EQ(candidates, 2);

  std::ostringstream json_line;
  write_cost_json_line(json_line, result, rows);
  const nlohmann::json json = nlohmann::json::parse(json_line.str());
  EXPECT_EQ(json["benchmark"], "cost");
  EXPECT_EQ(json["candidates"], 2);
  EXPECT_EQ(json["arms"]["parallel-jaw x rigid"]["all"]["candidates"], 2);
  EXPECT_TRUE(std::filesystem::exists(options.out / "cost.md"));
}

}  // namespace
}  // namespace grip::bench
