// `grip bench robustness` on a small plan: the plan follows its options and refuses bad ones,
// the per-step statistics are nearest-rank ones, and rigid jaws on three categories that used
// to stall Newton (box, capsule, plate) end every trial without a solver failure.
#include "bench/robustness/robustness_benchmark.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "bench/robustness/robustness_report.hpp"
#include "bench/robustness/robustness_trials.hpp"
#include "src/objects/object_library.hpp"

namespace grip::bench {
namespace {

TEST(RobustnessBench, DefaultPlanMeetsTheTrialCounts) {
  const std::vector<RobustnessSet> sets = plan_robustness(RobustnessOptions{});
  std::map<std::string, int> trials;
  std::map<std::string, std::set<std::string>> categories;
  for (const RobustnessSet& set : sets) {
    trials[set.gripper] += set.seeds * set.candidates;
    categories[set.gripper].insert(set.category);
  }
  EXPECT_GE(trials["parallel-jaw"], 384);
  EXPECT_GE(trials["fin-ray"], 48);
  EXPECT_GE(trials["leap"], 48);
  for (const auto& [gripper, names] : categories) {
    EXPECT_EQ(names.size(), objects::all_object_categories().size()) << gripper;
  }
}

TEST(RobustnessBench, PlanFollowsOptionsAndRefusesBadOnes) {
  RobustnessOptions options;
  options.grippers = {"fin-ray"};
  options.categories = {"box", "plate"};
  options.soft = false;
  options.seeds = 3;
  const std::vector<RobustnessSet> sets = plan_robustness(options);
  ASSERT_EQ(sets.size(), 2u);
  for (const RobustnessSet& set : sets) {
    EXPECT_EQ(set.gripper, "fin-ray");
    EXPECT_FALSE(set.soft);
    EXPECT_EQ(set.seeds, 3);
  }
  RobustnessOptions bad = options;
  bad.grippers = {"claw"};
  EXPECT_THROW(plan_robustness(bad), std::invalid_argument);
  bad = options;
  bad.categories = {"teacup"};
  EXPECT_THROW(plan_robustness(bad), std::invalid_argument);
  bad = options;
  bad.rigid = false;
  EXPECT_THROW(plan_robustness(bad), std::invalid_argument);
}

// The production models are the ones `grip trial` builds: a soft object meshed as `grip trial
// --soft` meshes it has more tets than the coarse model's, and the plan carries the choice.
TEST(RobustnessBench, ProductionModelsAreTheTrialsOwn) {
  RobustnessOptions options;
  options.grippers = {"fin-ray"};
  options.categories = {"cylinder"};
  options.rigid = false;
  options.production_models = true;
  const std::vector<RobustnessSet> sets = plan_robustness(options);
  ASSERT_EQ(sets.size(), 1u);
  EXPECT_TRUE(sets[0].production_models);
  EXPECT_FALSE(sets[0].fine_fin_ray);
  // The finer finger of grip bench labels --refine finger is carried the same way.
  options.fine_fin_ray = true;
  EXPECT_TRUE(plan_robustness(options).at(0).fine_fin_ray);
  RobustnessSet coarse = sets[0];
  coarse.production_models = false;
  const trial::TrialObject fine = make_object(sets[0], 1);
  const trial::TrialObject rough = make_object(coarse, 1);
  ASSERT_TRUE(fine.tets && rough.tets);
  EXPECT_GT(fine.tets->tets.rows(), 2 * rough.tets->tets.rows());
  EXPECT_NE(robustness_gripper_model("fin-ray", true), robustness_gripper_model("fin-ray", false));
  EXPECT_NE(robustness_object_model(true, true), robustness_object_model(true, false));
}

TEST(RobustnessBench, RankStatisticsOfAHistogram) {
  // 100 steps: 90 of 3 iterations, 9 of 7, 1 of 40.
  std::vector<long> counts(41, 0);
  counts[3] = 90;
  counts[7] = 9;
  counts[40] = 1;
  const RankStatistics s = rank_statistics(counts);
  EXPECT_EQ(s.count, 100);
  EXPECT_EQ(s.median, 3.0);
  EXPECT_EQ(s.p99, 7.0);  // rank 99 of 100
  EXPECT_EQ(s.max, 40.0);
  EXPECT_TRUE(std::isnan(rank_statistics({0, 0}).median));
}

TEST(RobustnessBench, RigidJawsEndWithoutSolverFailures) {
  RobustnessOptions options;
  options.grippers = {"parallel-jaw"};
  options.categories = {"box", "capsule", "plate"};
  options.soft = false;
  options.seeds = 1;
  options.candidates = 4;
  options.threads = 2;
  options.out = std::filesystem::path(::testing::TempDir()) / "robustness";
  const RobustnessResult result = run_robustness(options);
  ASSERT_GE(result.trials.size(), 8u) << "too few shapes took a candidate";
  for (const RobustnessTrial& t : result.trials) {
    EXPECT_NE(t.status, io::Status::kPending);
    EXPECT_NE(t.failure, io::FailureKind::kNewtonLimit)
        << t.category << " seed " << t.seed << " #" << t.candidate << ": " << t.failure_reason;
    EXPECT_NE(t.failure, io::FailureKind::kNumerical)
        << t.category << " seed " << t.seed << " #" << t.candidate << ": " << t.failure_reason;
    long steps = 0;
    for (const long n : t.steps_by_iterations) steps += n;
    // The histogram counts every accepted step, and the step a solver failure gave up on.
    const bool solver_failure =
        t.failure == io::FailureKind::kNewtonLimit || t.failure == io::FailureKind::kNumerical;
    EXPECT_EQ(steps, static_cast<long>(t.newton.steps) + (solver_failure ? 1 : 0));
  }

  const std::vector<RobustnessTally> rows = robustness_rows(result);
  ASSERT_FALSE(rows.empty());
  EXPECT_EQ(rows.back().trials, static_cast<int>(result.trials.size()));
  std::ostringstream line;
  write_robustness_json_line(line, result, rows);
  const nlohmann::json json = nlohmann::json::parse(line.str());
  EXPECT_EQ(json["benchmark"], "robustness");
  EXPECT_EQ(json["trials"], result.trials.size());
  EXPECT_EQ(json["failures"]["newton_limit"], 0);
  EXPECT_GT(json["newton_iterations_per_step"]["steps"].get<long>(), 0);
  write_robustness_files(options.out, result, rows);
  EXPECT_TRUE(std::filesystem::exists(options.out / "robustness.csv"));
  // Every row of each Markdown table has as many cells as its header.
  std::ifstream md(options.out / "robustness.md");
  long header_cells = -1;
  for (std::string line; std::getline(md, line);) {
    if (line.empty() || line[0] != '|') {
      header_cells = -1;
      continue;
    }
    const long cells = std::count(line.begin(), line.end(), '|');
    if (header_cells < 0) header_cells = cells;
    EXPECT_EQ(cells, header_cells) << line;
  }
}

}  // namespace
}  // namespace grip::bench
