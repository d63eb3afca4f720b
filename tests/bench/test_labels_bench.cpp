// `grip bench labels` on a small plan: the reference refines the numerics but keeps what the
// protocol measures in seconds and millimetres, bad options are refused, candidates pair up by
// (category, seed, candidate), the tally counts what the pairs say (per category too), and rigid
// jaws on a box hold every finger in contact at 50 N within 5 %.
#include "bench/labels/labels_benchmark.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "bench/labels/labels_report.hpp"
#include "src/objects/object_library.hpp"

namespace grip::bench {
namespace {

TEST(LabelsBench, ReferenceRefinesTheNumericsNotTheQuestion) {
  const trial::TrialParameters d;
  const trial::TrialParameters r = reference_parameters(d);
  EXPECT_EQ(r.sim.dt, d.sim.dt / 2);
  EXPECT_EQ(r.sim.newton_tol, d.sim.newton_tol / 10);
  EXPECT_EQ(r.sim.friction_lag_iterations, 2);
  // The same verdict threshold (m) and the same settling allowance (s).
  EXPECT_DOUBLE_EQ(r.displacement_threshold(), d.displacement_threshold());
  EXPECT_DOUBLE_EQ(r.settle_max_steps * r.sim.dt, d.settle_max_steps * d.sim.dt);
  EXPECT_DOUBLE_EQ(r.settle_steps * r.sim.dt, d.settle_steps * d.sim.dt);
  EXPECT_EQ(r.grip_force, d.grip_force);
  EXPECT_EQ(r.phase_duration, d.phase_duration);
}

TEST(LabelsBench, AReferenceCanRefineOneSettingAlone) {
  trial::TrialParameters d;
  d.sim.newton_tol = 1e-4;
  d.sim.friction_lag_iterations = 2;
  LabelsRefinement lag_only;
  lag_only.dt = lag_only.newton_tol = false;
  const trial::TrialParameters lag = reference_parameters(d, lag_only);
  EXPECT_EQ(lag.sim.friction_lag_iterations, 3);
  EXPECT_EQ(lag.sim.dt, d.sim.dt);
  EXPECT_EQ(lag.sim.newton_tol, d.sim.newton_tol);
  EXPECT_EQ(lag.settle_steps, d.settle_steps);
  EXPECT_EQ(lag.displacement_factor, d.displacement_factor);
  LabelsRefinement tol_only;
  tol_only.dt = tol_only.friction_lag = false;
  const trial::TrialParameters tol = reference_parameters(d, tol_only);
  EXPECT_EQ(tol.sim.newton_tol, d.sim.newton_tol / 10);
  EXPECT_EQ(tol.sim.friction_lag_iterations, 2);
  EXPECT_EQ(tol.sim.dt, d.sim.dt);
  // A convergence study's finer step: the same seconds and metres at dt / 4.
  LabelsRefinement quarter;
  quarter.dt_divisor = 4;
  const trial::TrialParameters fine = reference_parameters(d, quarter);
  EXPECT_EQ(fine.sim.dt, d.sim.dt / 4);
  EXPECT_EQ(fine.settle_steps, 4 * d.settle_steps);
  EXPECT_DOUBLE_EQ(fine.displacement_threshold(), d.displacement_threshold());
}

TEST(LabelsBench, RefusesBadOptions) {
  LabelsOptions options;
  options.seeds = 0;
  EXPECT_THROW(check_labels_options(options), std::invalid_argument);
  options.seeds = 1;
  options.arms = {{"gripper-x", false}};
  EXPECT_THROW(check_labels_options(options), std::invalid_argument);
  options.arms = {{"leap", false}};
  options.categories = {"teacup"};
  try {
    check_labels_options(options);
    FAIL() << "an unknown category was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("grip bench labels: ", 0), 0u) << e.what();
  }
  // A mesh reference needs a graded mesh to compare: production models, a growth above 0.
  options.categories.clear();
  options.refinement.mesh = true;
  options.production_models = true;
  options.soft_interior_growth = 0.0;
  EXPECT_THROW(check_labels_options(options), std::invalid_argument);
  options.soft_interior_growth = 0.5;
  EXPECT_NO_THROW(check_labels_options(options));
  options.production_models = false;
  EXPECT_THROW(check_labels_options(options), std::invalid_argument);
  // A finer finger is compared with the production one only.
  options.refinement.mesh = false;
  options.refinement.finger = true;
  try {
    check_labels_options(options);
    FAIL() << "--refine finger was accepted with the coarse models";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("--refine finger compares the production fin-ray finger"),
              std::string::npos)
        << e.what();
  }
  options.production_models = true;
  EXPECT_NO_THROW(check_labels_options(options));
}

TEST(LabelsBench, ForceSummaryCountsFingersInContactOfClosedTrials) {
  RobustnessTrial closed, open;
  closed.closed = true;
  closed.closing_forces = {49.0, 0.0, 53.0, 50.5};
  open.closing_forces = {10.0, 20.0};  // closing never ended: not counted
  const ForceSummary s = force_summary({&closed, &open}, 50.0, 2.5);
  EXPECT_EQ(s.fingers, 3);
  EXPECT_EQ(s.within, 2);
  EXPECT_EQ(s.min, 49.0);
  EXPECT_EQ(s.median, 50.5);
  EXPECT_EQ(s.max, 53.0);
}

TEST(LabelsBench, AllAsksForEveryCategoryOfTheLibrary) {
  LabelsOptions options;
  EXPECT_EQ(labels_categories(options), kLabelsCategories);
  options.categories = {"mug", "rod"};
  EXPECT_EQ(labels_categories(options), options.categories);
  options.categories = {"all"};
  const std::vector<std::string> all = labels_categories(options);
  ASSERT_EQ(all.size(), objects::all_object_categories().size());
  EXPECT_NE(std::find(all.begin(), all.end(), "torus"), all.end());
  options.arms = {{"parallel-jaw", false}};
  EXPECT_NO_THROW(check_labels_options(options));
}

TEST(LabelsBench, TheTallySplitsTheClosingForcesByCategory) {
  auto trial = [](std::string category, std::uint64_t candidate, std::vector<double> forces) {
    RobustnessTrial t;
    t.category = std::move(category);
    t.candidate = candidate;
    t.closed = true;
    t.closing_forces = std::move(forces);
    return t;
  };
  LabelsArmResult arm;
  arm.arm = {"fin-ray", false};
  arm.defaults.trials = {trial("mug", 0, {50.2, 49.1}), trial("bowl", 0, {31.0, 50.0}),
                         trial("mug", 1, {51.0, 48.0})};
  arm.reference.trials = arm.defaults.trials;
  LabelsResult result;
  result.arms = {arm};
  const LabelsArmTally t = labels_tallies(result).front();
  EXPECT_EQ(t.forces.fingers, 6);
  EXPECT_EQ(t.forces.within, 5);
  ASSERT_EQ(t.forces_by_category.size(), 2u);
  EXPECT_EQ(t.forces_by_category.at("mug").fingers, 4);
  EXPECT_EQ(t.forces_by_category.at("mug").within, 4);
  EXPECT_EQ(t.forces_by_category.at("bowl").fingers, 2);
  EXPECT_EQ(t.forces_by_category.at("bowl").within, 1);
  EXPECT_EQ(t.forces_by_category.at("bowl").min, 31.0);
}

// Rigid jaws on `candidates` candidates of one box, on two threads.
LabelsOptions rigid_jaws_on_a_box(int candidates) {
  LabelsOptions options;
  options.arms = {{"parallel-jaw", false}};
  options.categories = {"box"};
  options.seeds = 1;
  options.candidates = candidates;
  options.threads = 2;
  return options;
}

TEST(LabelsBench, RigidJawsOnABoxHoldTheGripForceAndTheTallyCountsThePairs) {
  LabelsOptions options = rigid_jaws_on_a_box(3);
  options.out = std::filesystem::path(::testing::TempDir()) / "labels";
  const LabelsResult result = run_labels(options);
  ASSERT_EQ(result.arms.size(), 1u);
  const std::vector<LabelsPair> pairs = pair_trials(result.arms.front());
  ASSERT_EQ(pairs.size(), 3u);
  int agree = 0;
  for (const LabelsPair& pair : pairs) {
    ASSERT_NE(pair.reference, nullptr);
    EXPECT_EQ(pair.reference->candidate, pair.defaults->candidate);
    EXPECT_EQ(pair.reference->seed, pair.defaults->seed);
    agree += pair.defaults->status == pair.reference->status;
  }
  const std::vector<LabelsArmTally> tallies = labels_tallies(result);
  ASSERT_EQ(tallies.size(), 1u);
  const LabelsArmTally& t = tallies.front();
  EXPECT_EQ(t.arm, "parallel-jaw x rigid");
  EXPECT_EQ(t.trials, 3);
  EXPECT_EQ(t.agree, agree);
  EXPECT_EQ(t.forces.fingers, 6);
  EXPECT_EQ(t.forces.within, 6);

  std::ostringstream line;
  write_labels_json_line(line, result, tallies);
  const nlohmann::json json = nlohmann::json::parse(line.str());
  EXPECT_EQ(json["benchmark"], "labels");
  EXPECT_EQ(json["arms"][0]["candidates"], 3);
  EXPECT_EQ(json["arms"][0]["same_verdict"], agree);
  write_labels_files(options.out, result, tallies);
  std::ifstream csv(options.out / "labels.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header.rfind("arm,category,seed,candidate,verdict,verdict_reference,", 0), 0u);
  int rows = 0;
  for (std::string row; std::getline(csv, row);) ++rows;
  EXPECT_EQ(rows, 3);
}

TEST(LabelsBench, WithoutARefinementNoReferenceRunsAndTheComparisonIsLeftEmpty) {
  LabelsOptions options = rigid_jaws_on_a_box(2);
  options.refinement = {false, 2, false, false, false, false};
  ASSERT_FALSE(options.refinement.any());
  const LabelsResult result = run_labels(options);
  ASSERT_EQ(result.arms.size(), 1u);
  EXPECT_EQ(result.arms.front().defaults.trials.size(), 2u);
  EXPECT_TRUE(result.arms.front().reference.trials.empty());
  const std::vector<LabelsArmTally> tallies = labels_tallies(result);
  EXPECT_EQ(tallies.front().candidates, 2);
  EXPECT_EQ(tallies.front().trials, 0);
  EXPECT_EQ(tallies.front().forces.fingers, 4);
  std::ostringstream table;
  write_labels_table(table, tallies);
  EXPECT_NE(table.str().find("| parallel-jaw x rigid | 2 | - | - |"), std::string::npos)
      << table.str();
}

}  // namespace
}  // namespace grip::bench
