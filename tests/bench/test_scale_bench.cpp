// The farm model of `grip bench scale`: schedules worked out by hand, its bounds, the commit
// model's fit and the trial-cost inputs.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "bench/scale/commit_fit.hpp"
#include "bench/scale/farm_model.hpp"
#include "bench/scale/trial_costs.hpp"

namespace grip::bench {
namespace {

// One rigid object, one gripper: every candidate in pair 0.
ModelJob one_pair_job(const std::vector<double>& costs, int batch, int round_batches) {
  ModelJob job;
  job.object_soft = {false};
  job.candidate_seconds = costs;
  job.candidate_pair.assign(costs.size(), 0);
  job.class_mean = {1.0};
  job.work_unit_size = batch;
  job.round_work_units = round_batches;
  return job;
}

TEST(FarmModel, EqualCostsAndFreeCommitsScalePerfectly) {
  const ModelJob job = one_pair_job(std::vector<double>(64, 2.0), 2, 4);
  const FarmCosts free;  // every cost but the trials' 0
  const double one = simulate_farm(job, free, 1).total;
  EXPECT_DOUBLE_EQ(one, 128.0);
  for (const int ranks : {2, 4, 8}) {
    const ModelRun run = simulate_farm(job, free, ranks);
    EXPECT_DOUBLE_EQ(one / (ranks * run.total), 1.0) << ranks << " ranks";
    EXPECT_DOUBLE_EQ(run.idle, 0.0);
    EXPECT_DOUBLE_EQ(run.work, 128.0);
  }
}

TEST(FarmModel, OneHeavyTrialBoundsTheTimeFromBelow) {
  std::vector<double> costs(40, 0.5);
  costs[17] = 100.0;
  const ModelJob job = one_pair_job(costs, 4, 2);
  FarmCosts costs_model;
  costs_model.unit_commit = {0.01, 0, 0};
  costs_model.commit = {0.01, 0.001, 0};
  ModelOptions rounds;
  rounds.rounds = true;
  for (const int ranks : {1, 2, 8, 64, 4096}) {
    for (const ModelOptions& options : {ModelOptions{}, rounds}) {
      const ModelRun run = simulate_farm(job, costs_model, ranks, options);
      EXPECT_GE(run.total, 100.0 + 3 * 0.5) << ranks << " ranks";  // its work unit: 4 trials
    }
  }
  // With more ranks than work units the heavy unit alone sets the trial phase, then its commit.
  const ModelRun wide = simulate_farm(job, costs_model, 64);
  EXPECT_NEAR(wide.trial_phase, 101.5 + 0.01, 1e-12);
  EXPECT_EQ(wide.rounds, 1u);
  const ModelRun wide_rounds = simulate_farm(job, costs_model, 64, rounds);
  EXPECT_NEAR(wide_rounds.trial_phase, 101.5 + costs_model.commit.seconds(64, 0), 1e-12);
  EXPECT_EQ(wide_rounds.rounds, 1u);
}

// The rounds what-if: two ranks, work units of one candidate, rounds of 2 units per rank:
//   round 0, units 5 1 1 1: rank 0 takes 5 (busy to t=5), rank 1 takes 1, 1, 1 (to t=3), then
//     both find the round handed out; rank 1 idles 2 s; commit 0.5 + 0.25 log2(2) = 0.75 s;
//   round 1, units 2 2: one each, to 5.75 + 2 = 7.75; commit 0.75: trials end at 8.5.
// Start-up 1 s and the one object's preparation 0.5 s come first: 10 s.
TEST(FarmModel, SmallScheduleMatchesTheHandWorkedOne) {
  const ModelJob job = one_pair_job({5, 1, 1, 1, 2, 2}, 1, 2);
  FarmCosts costs;
  costs.startup = 1.0;
  costs.prepare_rigid = 0.5;
  costs.commit = {0.5, 0.25, 0};
  ModelOptions rounds;
  rounds.rounds = true;
  const ModelRun run = simulate_farm(job, costs, 2, rounds);
  EXPECT_EQ(run.units, 6u);
  EXPECT_EQ(run.rounds, 2u);
  EXPECT_DOUBLE_EQ(run.plan, 0.5);
  EXPECT_DOUBLE_EQ(run.trial_phase, 8.5);
  EXPECT_DOUBLE_EQ(run.total, 10.0);
  EXPECT_DOUBLE_EQ(run.idle, 2.0);
  EXPECT_DOUBLE_EQ(run.work, 12.0);
  EXPECT_DOUBLE_EQ(run.committing, 2 * 2 * 0.75);
}

TEST(FarmModel, ClaimsQueueAtRankZero) {
  // 4 ranks, 4 free units: 8 claims (4 granted, 4 refused), each holding the
  // counter 1 s, all issued at t=0 (the refusals as soon as a rank's unit ends).
  const ModelJob job = one_pair_job({0, 0, 0, 0}, 1, 1);
  FarmCosts costs;
  costs.claim.service = 1.0;
  const ModelRun run = simulate_farm(job, costs, 4);
  EXPECT_DOUBLE_EQ(run.trial_phase, 8.0);
  EXPECT_DOUBLE_EQ(run.claiming, 1 + 2 + 3 + 4 + 4 + 4 + 4 + 4);
}

TEST(FarmModel, SceneBuildsFollowTheRunnersKeptPairs) {
  // Pairs A B C A on one rank: the runner cache keeps two, oldest out first, so four builds.
  ModelJob job;
  job.object_soft = {false, false, false};
  job.candidate_seconds = {1, 1, 1, 1};
  job.candidate_pair = {0, 1, 2, 0};
  job.class_mean = {1, 1, 1};
  job.work_unit_size = 4;
  job.round_work_units = 8;
  FarmCosts costs;
  costs.scene_build = 10.0;
  EXPECT_DOUBLE_EQ(simulate_farm(job, costs, 1).trial_phase, 4 + 4 * 10.0);
  job.candidate_pair = {0, 1, 0, 1};  // A B A B: two builds
  EXPECT_DOUBLE_EQ(simulate_farm(job, costs, 1).trial_phase, 4 + 2 * 10.0);
}

TEST(FarmModel, WorkUnitsAreCutAtEachPairAndAtTheBatchSize) {
  ModelJob job;
  job.object_soft = {false, true};
  job.candidate_seconds.assign(8, 1.0);
  job.candidate_pair = {0, 0, 0, 0, 0, 1, 1, 1};
  job.class_mean = {1, 1};
  job.work_unit_size = 4;
  EXPECT_EQ(simulate_farm(job, FarmCosts{}, 1).units, 3u);
  job.work_unit_size = 2;
  EXPECT_EQ(simulate_farm(job, FarmCosts{}, 1).units, 5u);
}

TEST(FarmModel, PlanningIsSharedRoundRobin) {
  ModelJob job = one_pair_job({1, 1, 1}, 1, 1);
  job.object_soft = {true, false, true};
  job.candidate_pair = {0, 1, 2};
  job.class_mean = {1, 1, 1};
  FarmCosts costs;
  costs.prepare_soft = 4;
  costs.prepare_rigid = 1;
  costs.synthesis = 0.5;
  EXPECT_DOUBLE_EQ(simulate_farm(job, costs, 1).plan, 9 + 1.5);
  // Two ranks: objects 0 and 2 (both soft) on rank 0; pairs 0 and 2 synthesized there too.
  EXPECT_DOUBLE_EQ(simulate_farm(job, costs, 2).plan, 8 + 1.0);
}

TEST(FarmModel, HeaviestFirstAndUnitCommitsHelpAHeavyTail) {
  // Soft pairs cost 10x: in id order, rounds wait for them.
  ModelJob job;
  job.grippers = 1;
  for (int o = 0; o < 32; ++o) {
    job.object_soft.push_back(o % 4 == 3);
    job.class_mean.push_back(o % 4 == 3 ? 10.0 : 1.0);
    for (int c = 0; c < 4; ++c) {
      job.candidate_seconds.push_back(job.class_mean.back());
      job.candidate_pair.push_back(o);
    }
  }
  job.work_unit_size = 4;
  job.round_work_units = 2;
  const FarmCosts costs;
  ModelOptions rounds;
  rounds.rounds = true;
  const double before = simulate_farm(job, costs, 8, rounds).trial_phase;
  ModelOptions heaviest = rounds;
  heaviest.order = UnitOrder::kHeaviestFirst;
  EXPECT_LT(simulate_farm(job, costs, 8, heaviest).trial_phase, before);
  EXPECT_LT(simulate_farm(job, costs, 8).trial_phase, before);
  EXPECT_EQ(simulate_farm(job, costs, 8).rounds, 1u);
  EXPECT_GT(simulate_farm(job, costs, 8, rounds).rounds, 1u);
}

TEST(FarmModel, UnitCommitsShareTheFile) {
  // Two ranks end a one-candidate unit each at t=1 and write 1 byte at 1 byte/s: the second
  // write waits for the first (1-2, 2-3); the refused claims follow at 2 and 3.
  const ModelJob job = one_pair_job({1, 1}, 1, 1);
  FarmCosts costs;
  costs.bytes_per_candidate = 1;
  costs.unit_commit = {0, 5.0, 1.0};  // a unit's commit has no collective: no log2 term
  costs.commit = {100, 100, 1e-3};    // the rounds' commit, unused
  const ModelRun run = simulate_farm(job, costs, 2);
  EXPECT_DOUBLE_EQ(run.trial_phase, 3.0);
  EXPECT_DOUBLE_EQ(run.committing, 1.0 + 2.0);
  EXPECT_DOUBLE_EQ(run.idle, 1.0);
}

TEST(FarmModel, RankZeroPaysTheOtherRanksJournalLines) {
  // Three ranks end a free unit each at t=1; rank 0 appends ranks 1 and 2's ids as one line
  // (0.5 s) before its next claim, which finds everything handed out: the trial phase ends at
  // 1.5, ranks 1 and 2 idle 0.5 s each.
  const ModelJob job = one_pair_job({1, 1, 1}, 1, 1);
  FarmCosts costs;
  costs.journal_line = 0.5;
  const ModelRun run = simulate_farm(job, costs, 3);
  EXPECT_DOUBLE_EQ(run.trial_phase, 1.5);
  EXPECT_DOUBLE_EQ(run.committing, 0.5);
  EXPECT_DOUBLE_EQ(run.idle, 1.0);
  // Rank 1's unit ends at 1.1 (a line to 1.6), rank 2's and 3's while it is written: one more
  // line holds both (1.6 to 2.1), written while rank 0 waits.
  const ModelRun spread = simulate_farm(one_pair_job({1, 1.1, 1.2, 1.3}, 1, 1), costs, 4);
  EXPECT_DOUBLE_EQ(spread.committing, 1.0);
  EXPECT_DOUBLE_EQ(spread.trial_phase, 2.1);
}

TEST(FarmModel, RefusesNonsense) {
  const ModelJob job = one_pair_job({1}, 1, 1);
  EXPECT_THROW(simulate_farm(job, FarmCosts{}, 0), std::invalid_argument);
  EXPECT_THROW(simulate_farm(one_pair_job({1}, 0, 1), FarmCosts{}, 1), std::invalid_argument);
}

TEST(CommitFit, RecoversExactConstants) {
  const CommitModel truth{0.01, 0.004, 2e8};
  std::vector<CommitPoint> points;
  for (const int ranks : {1, 2, 3}) {
    for (const double bytes : {1e4, 1e7})
      points.push_back({ranks, bytes, truth.seconds(ranks, bytes)});
  }
  const CommitModel fit = fit_commit_model(points);
  EXPECT_NEAR(fit.latency, 0.01, 1e-9);
  EXPECT_NEAR(fit.per_log2, 0.004, 1e-9);
  EXPECT_NEAR(fit.bandwidth, 2e8, 1.0);
}

TEST(CommitFit, AUnitCommitHasNoLog2Term) {
  std::vector<CommitPoint> points;
  for (const int ranks : {1, 2, 3}) {
    for (const double bytes : {1e3, 1e6}) points.push_back({ranks, bytes, 0.005 + bytes / 1e8});
  }
  const CommitModel fit = fit_unit_commit_model(points);
  EXPECT_NEAR(fit.latency, 0.005, 1e-9);
  EXPECT_DOUBLE_EQ(fit.per_log2, 0.0);
  EXPECT_NEAR(fit.bandwidth, 1e8, 1.0);
  // A slope below zero (bigger writes faster, noise) is unlimited bandwidth: the mean.
  const CommitModel flat = fit_unit_commit_model({{1, 1e3, 0.004}, {2, 1e6, 0.002}});
  EXPECT_NEAR(flat.latency, 0.003, 1e-12);
  EXPECT_DOUBLE_EQ(flat.bandwidth, 0.0);
}

TEST(CommitFit, DropsATermThatFitsBelowZero) {
  // Commits that get faster with more ranks: the log2 term is left at zero.
  const std::vector<CommitPoint> points = {{1, 0, 0.02}, {2, 0, 0.015}, {4, 0, 0.01}};
  const CommitModel fit = fit_commit_model(points);
  EXPECT_EQ(fit.per_log2, 0.0);
  EXPECT_NEAR(fit.latency, 0.015, 1e-12);
  EXPECT_TRUE(fit.latency >= 0);
}

TEST(TrialCosts, SampledJobFollowsItsShapeAndSeed) {
  const CostSamples samples = {{"fin-ray x rigid", {1, 2, 3}}, {"fin-ray x soft", {10, 20}}};
  const ModelJob job = sampled_job(samples, {"fin-ray"}, 12, 100, 0.25, 7);
  EXPECT_EQ(job.candidate_seconds.size(), 100u);
  EXPECT_EQ(std::count(job.object_soft.begin(), job.object_soft.end(), true), 3);
  for (std::size_t id = 0; id < job.candidate_seconds.size(); ++id) {
    const bool soft = job.object_soft[job.candidate_pair[id]];
    EXPECT_EQ(soft, job.candidate_seconds[id] >= 10) << id;
  }
  EXPECT_DOUBLE_EQ(job.class_mean[3], 15.0);
  EXPECT_EQ(sampled_job(samples, {"fin-ray"}, 12, 100, 0.25, 7).candidate_seconds,
            job.candidate_seconds);
  EXPECT_NE(sampled_job(samples, {"fin-ray"}, 12, 100, 0.25, 8).candidate_seconds,
            job.candidate_seconds);
  EXPECT_THROW(sampled_job(samples, {"leap"}, 12, 100, 0.25, 7), std::invalid_argument);
}

TEST(TrialCosts, ReadsTheTrialBenchmarksRunsAtTheDefaults) {
  const std::filesystem::path file =
      std::filesystem::path(::testing::TempDir()) / "scale_trial_costs.csv";
  std::ofstream(file) << "arm,category,settings,wall_s\n"
                         "fin-ray x soft,box,defaults,14.5\n"
                         "fin-ray x soft,box,reference,99\n"
                         "fin-ray x rigid,box,defaults,6.5\n";
  const CostSamples samples = read_cost_samples(file);
  ASSERT_EQ(samples.size(), 2u);
  EXPECT_EQ(samples.at("fin-ray x soft"), std::vector<double>{14.5});
  EXPECT_EQ(samples.at("fin-ray x rigid"), std::vector<double>{6.5});
  std::ofstream(file) << "arm,settings\nx,defaults\n";
  EXPECT_THROW(read_cost_samples(file), std::runtime_error);
}

}  // namespace
}  // namespace grip::bench
