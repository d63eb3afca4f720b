// `grip bench model` on tiny settings: each lean model ends where the full one does within a
// stated tolerance, and each switch changes what it claims (DOFs, iterations, friction
// contacts). Freezing converged environments is the batch's default, and it leaves every
// environment bit-identical to a solo run; holding converged steps open changes nothing solo.
#include "bench/model/model_benchmark.hpp"

#include <gtest/gtest.h>

#include <sstream>

#include "bench/model/squeeze_scene.hpp"
#include "solver/batch/batch.hpp"

namespace grip::bench {
namespace {

// A 2 x 2 x 2-cell cube (27 vertices) between 2 cm-cell pads, held for 5 steps.
SqueezeOptions tiny() {
  SqueezeOptions options;
  options.object_cell = 0.02;
  options.pad_cell = 0.02;
  options.hold_steps = 5;
  return options;
}

constexpr int kCubeVertices = 27;
constexpr int kPadVertices = 2 * 4 * 4;  // one cell deep, 3 x 3 cells across

void expect_ran(const SqueezeResult& result) {
  EXPECT_FALSE(result.failed) << result.failure;
  EXPECT_GT(result.closing_force, 1.0) << "the pads must squeeze the cube";
}

TEST(ModelBench, AffineCubeEndsWhereAStiffFemCubeDoes) {
  SqueezeOptions lean = tiny(), full = tiny();
  full.fem_object = true;
  const SqueezeResult a = run_squeeze(lean, make_squeeze_scene(lean));
  const SqueezeResult b = run_squeeze(full, make_squeeze_scene(full));
  expect_ran(a);
  expect_ran(b);
  EXPECT_EQ(a.free_dofs, 12);
  EXPECT_EQ(b.free_dofs, 3 * kCubeVertices);
  const SqueezeError error = squeeze_error(a, b);
  EXPECT_LT(error.vertex_m, 2e-5);  // 20 um on a 4 cm cube
  EXPECT_LT(error.rotation_rad, 1e-3);
  // The pads stop on a 1 um step of a stiff barrier: the force at the stop step differs by
  // more than the cube's few microns of give.
  EXPECT_LT(error.force_relative, 0.1);
}

TEST(ModelBench, KinematicPadsSqueezeLikeStiffPinnedFemPads) {
  SqueezeOptions lean = tiny(), full = tiny();
  full.fem_fingers = true;
  const SqueezeResult a = run_squeeze(lean, make_squeeze_scene(lean));
  const SqueezeResult b = run_squeeze(full, make_squeeze_scene(full));
  expect_ran(a);
  expect_ran(b);
  EXPECT_EQ(a.free_dofs, 12);
  // Each pad's back face (half its vertices) is pinned to its jaw; the rest are solved for.
  EXPECT_EQ(b.free_dofs, 12 + 2 * 3 * kPadVertices / 2);
  const SqueezeError error = squeeze_error(a, b);
  EXPECT_LT(error.vertex_m, 2e-5);
  EXPECT_LT(error.rotation_rad, 1e-3);
  EXPECT_LT(error.force_relative, 0.05);
}

// Three cubes turned differently about the closing axis, so that their contacts differ and they
// converge at different iterations.
std::vector<Eigen::Isometry3d> turned_cubes() {
  std::vector<Eigen::Isometry3d> placements;
  for (const double degrees : {0.0, 7.0, -4.0}) {
    Eigen::Isometry3d placement = Eigen::Isometry3d::Identity();
    placement.translate(Eigen::Vector3d(0.0, 1e-4 * degrees, 0.0));
    placement.rotate(Eigen::AngleAxisd(degrees * M_PI / 180.0, Eigen::Vector3d::UnitX()));
    placements.push_back(placement);
  }
  return placements;
}

struct BatchRun {
  long iterations = 0;
  long frozen = 0;
  bool all_iterate_every_round = true;  // every stepping environment, in every round
  std::vector<SqueezeResult> results;
};

BatchRun run_batch(const SqueezeOptions& options, const SqueezeScene& scene, bool freeze) {
  solver::Batch batch(1);
  if (!freeze) batch.set_policy({.freeze_converged = false});
  for (const Eigen::Isometry3d& placement : turned_cubes()) {
    batch.environment(batch.add(scene.model)).place(0, placement);
  }
  BatchRun run;
  std::vector<SqueezeProgress> progress(batch.size());
  for (;;) {
    for (int e = 0; e < batch.size(); ++e) {
      if (batch.active(e) &&
          !next_squeeze_step(options, scene, batch.environment(e), progress[e])) {
        batch.retire(e);
      }
    }
    if (!batch.any_active()) break;
    const solver::BatchStepReport report = batch.step();
    run.iterations += report.iterations;
    run.frozen += report.frozen;
    run.all_iterate_every_round =
        run.all_iterate_every_round && report.iterations == long{report.stepped} * report.rounds;
  }
  for (int e = 0; e < batch.size(); ++e)
    run.results.push_back(squeeze_result(scene, batch.environment(e)));
  return run;
}

TEST(ModelBench, AlwaysActiveBatchIteratesMoreToTheSameEnd) {
  const SqueezeOptions options = tiny();
  const SqueezeScene scene = make_squeeze_scene(options);
  const BatchRun frozen = run_batch(options, scene, true);
  const BatchRun active = run_batch(options, scene, false);
  EXPECT_GT(frozen.frozen, 0) << "the cubes must converge at different iterations";
  EXPECT_EQ(active.frozen, 0);
  EXPECT_FALSE(frozen.all_iterate_every_round);
  EXPECT_TRUE(active.all_iterate_every_round);
  EXPECT_GT(active.iterations, frozen.iterations);
  for (std::size_t e = 0; e < frozen.results.size(); ++e) {
    expect_ran(frozen.results[e]);
    expect_ran(active.results[e]);
    // The extra iterations start from converged states: they move nothing that matters.
    const SqueezeError error = squeeze_error(frozen.results[e], active.results[e]);
    EXPECT_LT(error.vertex_m, 1e-6);
    EXPECT_LT(error.force_relative, 0.01);
  }
}

TEST(ModelBench, FreezingIsTheDefaultAndMatchesSoloRunsBitForBit) {
  const SqueezeOptions options = tiny();
  const SqueezeScene scene = make_squeeze_scene(options);
  const BatchRun batch = run_batch(options, scene, true);
  const std::vector<Eigen::Isometry3d> placements = turned_cubes();
  for (std::size_t e = 0; e < placements.size(); ++e) {
    const SqueezeResult solo = run_squeeze(options, scene, placements[e]);
    EXPECT_EQ(solo.dofs, batch.results[e].dofs);
    EXPECT_EQ(solo.newton_iterations, batch.results[e].newton_iterations);
  }
  // Solo, a held step is finished at once by step(): the same trajectory.
  solver::Environment plain(scene.model), holding(scene.model);
  holding.set_policy({.freeze_converged = false});
  SqueezeProgress plain_progress, holding_progress;
  while (next_squeeze_step(options, scene, plain, plain_progress)) {
    ASSERT_TRUE(next_squeeze_step(options, scene, holding, holding_progress));
    ASSERT_TRUE(plain.step());
    ASSERT_TRUE(holding.step());
  }
  EXPECT_FALSE(next_squeeze_step(options, scene, holding, holding_progress));
  EXPECT_EQ(plain.dofs(), holding.dofs());
}

TEST(ModelBench, FrictionTermsAtZeroMuAddContactsButChangeNothing) {
  SqueezeOptions options = tiny();
  options.friction = 0.0;
  options.ground = true;
  const SqueezeScene scene = make_squeeze_scene(options);
  const SqueezeResult skipped = run_squeeze(options, scene);
  const SqueezeResult assembled = run_squeeze(options, scene, Eigen::Isometry3d::Identity(), true);
  expect_ran(skipped);
  expect_ran(assembled);
  EXPECT_EQ(skipped.friction_contacts, 0);
  EXPECT_GT(assembled.friction_contacts, 0);
  EXPECT_EQ(skipped.newton_iterations, assembled.newton_iterations);
  EXPECT_LT(squeeze_error(skipped, assembled).vertex_m, 1e-12);
}

TEST(ModelBench, BenchmarkReportsEveryComparison) {
  ModelBenchmarkOptions options;
  options.repeats = 1;
  options.batch_envs = 2;
  options.scene = tiny();
  std::ostringstream log;
  const std::vector<ModelComparison> rows = run_model_benchmark(options, log);
  ASSERT_EQ(rows.size(), 4u);
  for (const ModelComparison& row : rows) {
    EXPECT_TRUE(row.failure.empty()) << row.name << ": " << row.failure;
    EXPECT_EQ(row.lean_runs.size(), 1u);
    EXPECT_EQ(row.full_runs.size(), 1u);
  }
  EXPECT_LT(rows[0].lean_dofs, rows[0].full_dofs);
  EXPECT_LT(rows[1].lean_dofs, rows[1].full_dofs);
  EXPECT_LE(rows[2].lean_iterations, rows[2].full_iterations);
  EXPECT_GT(rows[2].frozen_fraction, 0.0);
  EXPECT_EQ(rows[3].lean_iterations, rows[3].full_iterations);
  std::ostringstream csv;
  write_model_csv(csv, rows);
  const std::string text = csv.str();
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 5);  // a header and four rows
}

}  // namespace
}  // namespace grip::bench
