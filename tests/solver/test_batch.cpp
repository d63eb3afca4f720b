// The batch engine: environments stepped together end bit-identical to solo runs of
// themselves for any thread count, a failing environment fails alone with its reason, and
// converged environments sit frozen while the others iterate.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "solver/batch/batch.hpp"
#include "tests/solver/scene_builders.hpp"

namespace grip::solver::testing {
namespace {

// A soft cube dropped onto a kinematic floor: many contacts appear within a few steps.
SceneDescription soft_drop() {
  SceneDescription scene;
  scene.sim.gravity = Eigen::Vector3d(0, 0, -9.81);
  scene.sim.dt = 0.01;
  scene.bodies = {rigid_box("floor", BodyType::kKinematic, {0.2, 0.2, 0.02}, {0, 0, -0.01}),
                  soft_box("cube", {0.03, 0.03, 0.03}, 0.01, {0, 0, 0.0165}, 1e5)};
  return scene;
}

// A rigid box sliding down a 30 degree ramp with mu = 0.3.
SceneDescription rigid_slide() { return box_on_ramp(std::numbers::pi / 6, 0.3, 1000.0, 0.005); }

// A soft cube squeezed between two kinematic plates closing at 0.05 m/s each.
SceneDescription soft_squeeze() {
  SceneDescription scene;
  scene.sim.gravity = Eigen::Vector3d::Zero();
  scene.sim.dt = 0.01;
  BodyDescription left = rigid_box("left", BodyType::kKinematic, {0.01, 0.1, 0.1}, {-0.0205, 0, 0});
  BodyDescription right =
      rigid_box("right", BodyType::kKinematic, {0.01, 0.1, 0.1}, {0.0205, 0, 0});
  left.script.velocity = Eigen::Vector3d(0.05, 0, 0);
  right.script.velocity = Eigen::Vector3d(-0.05, 0, 0);
  scene.bodies = {soft_box("cube", {0.03, 0.03, 0.03}, 0.01, Eigen::Vector3d::Zero(), 1e5), left,
                  right};
  return scene;
}

// A box resting on the floor from the start: converges in the fewest iterations.
SceneDescription resting_box() {
  SceneDescription scene;
  scene.sim.gravity = Eigen::Vector3d(0, 0, -9.81);
  scene.bodies = {rigid_box("floor", BodyType::kKinematic, {0.2, 0.2, 0.02}, {0, 0, -0.01}),
                  rigid_box("box", BodyType::kAffine, {0.04, 0.04, 0.04}, {0, 0, 0.0205})};
  return scene;
}

struct Trajectory {
  std::vector<Eigen::VectorXd> dofs;  // after each step
  std::vector<int> iterations;        // Newton iterations of each step
  std::string failure;
};

Trajectory solo(const SceneDescription& scene, int steps) {
  Environment env(Model::build(scene));
  Trajectory t;
  for (int s = 0; s < steps && env.step(); ++s) {
    t.dofs.push_back(env.dofs());
    t.iterations.push_back(env.last_step().newton_iterations);
  }
  t.failure = env.failure();
  return t;
}

std::vector<Trajectory> batched(const std::vector<SceneDescription>& scenes, int steps,
                                int threads) {
  Batch batch(threads);
  for (const SceneDescription& scene : scenes) batch.add(Model::build(scene));
  std::vector<Trajectory> result(scenes.size());
  for (int s = 0; s < steps; ++s) {
    std::vector<char> was_active(scenes.size());
    for (int i = 0; i < batch.size(); ++i) was_active[i] = batch.active(i);
    batch.step();
    for (int i = 0; i < batch.size(); ++i) {
      const Environment& env = batch.environment(i);
      if (was_active[i] && !env.failed()) {
        result[i].dofs.push_back(env.dofs());
        result[i].iterations.push_back(env.last_step().newton_iterations);
      }
    }
  }
  for (int i = 0; i < batch.size(); ++i) result[i].failure = batch.environment(i).failure();
  return result;
}

void expect_identical(const Trajectory& a, const Trajectory& b, const std::string& what) {
  ASSERT_EQ(a.dofs.size(), b.dofs.size()) << what;
  EXPECT_EQ(a.iterations, b.iterations) << what;
  EXPECT_EQ(a.failure, b.failure) << what;
  for (std::size_t s = 0; s < a.dofs.size(); ++s) {
    // Bit for bit: exact equality of every DOF, not a tolerance.
    ASSERT_TRUE(a.dofs[s] == b.dofs[s]) << what << ", step " << s << ": max difference "
                                        << (a.dofs[s] - b.dofs[s]).cwiseAbs().maxCoeff();
  }
}

class BatchThreads : public ::testing::TestWithParam<int> {};

TEST_P(BatchThreads, DifferentScenesEqualTheirSoloRunsBitForBit) {
  const std::vector<SceneDescription> scenes = {soft_drop(), rigid_slide(), soft_squeeze(),
                                                resting_box()};
  constexpr int kSteps = 8;
  const std::vector<Trajectory> together = batched(scenes, kSteps, GetParam());
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    const Trajectory alone = solo(scenes[i], kSteps);
    ASSERT_EQ(alone.dofs.size(), static_cast<std::size_t>(kSteps)) << alone.failure;
    expect_identical(alone, together[i], "scene " + std::to_string(i));
  }
}

TEST_P(BatchThreads, AFailingEnvironmentFailsAloneWithItsReason) {
  // An intersecting start (the box sunk into the floor) and an iteration cap too small to
  // converge, between two healthy scenes.
  SceneDescription sunk = resting_box();
  sunk.bodies[1].pose.position.z() = 0.015;
  SceneDescription capped = soft_drop();
  capped.sim.max_newton_iters = 1;
  const std::vector<SceneDescription> scenes = {soft_drop(), sunk, rigid_slide(), capped};
  constexpr int kSteps = 6;
  const std::vector<Trajectory> together = batched(scenes, kSteps, GetParam());
  EXPECT_NE(together[1].failure.find("intersecting start"), std::string::npos)
      << together[1].failure;
  EXPECT_TRUE(together[1].dofs.empty());
  EXPECT_NE(together[3].failure.find("Newton did not converge in 1 iterations"), std::string::npos)
      << together[3].failure;
  for (std::size_t i : {0u, 2u}) {
    expect_identical(solo(scenes[i], kSteps), together[i], "healthy scene " + std::to_string(i));
  }
  // The failures are what the same scenes give alone.
  EXPECT_EQ(solo(sunk, kSteps).failure, together[1].failure);
  EXPECT_EQ(solo(capped, kSteps).failure, together[3].failure);
}

INSTANTIATE_TEST_SUITE_P(OneAndTwoThreads, BatchThreads, ::testing::Values(1, 2));

TEST(Batch, ConvergedEnvironmentsSitFrozenWhileOthersIterate) {
  Batch batch(2);
  batch.add(Model::build(resting_box()));
  batch.add(Model::build(soft_drop()));
  batch.add(Model::build(soft_squeeze()));
  long frozen_total = 0;
  for (int s = 0; s < 5; ++s) {
    const BatchStepReport report = batch.step();
    ASSERT_EQ(report.stepped, 3);
    ASSERT_EQ(report.failed, 0);
    int most = 0;
    long iterations = 0;
    long frozen = 0;
    for (int i = 0; i < batch.size(); ++i) {
      most = std::max(most, batch.environment(i).last_step().newton_iterations);
      iterations += batch.environment(i).last_step().newton_iterations;
    }
    for (int i = 0; i < batch.size(); ++i) {
      frozen += most - batch.environment(i).last_step().newton_iterations;
    }
    // Rounds run until the slowest environment converges; every other one is frozen for the
    // rounds it does not need, and iterates exactly as often as alone.
    EXPECT_EQ(report.rounds, most);
    EXPECT_EQ(report.iterations, iterations);
    EXPECT_EQ(report.frozen, frozen);
    frozen_total += frozen;
  }
  // The box at rest needs fewer iterations than the squeezed cube, so it did sit frozen.
  EXPECT_LT(batch.environment(0).statistics().newton_iterations,
            batch.environment(2).statistics().newton_iterations);
  EXPECT_GT(frozen_total, 0);
  EXPECT_EQ(batch.environment(0).statistics().steps, 5);
}

TEST(Batch, RetiredEnvironmentsStopWhereTheyAre) {
  Batch batch(1);
  batch.add(Model::build(soft_drop()));
  batch.add(Model::build(soft_drop()));
  batch.step();
  batch.retire(0);
  const Eigen::VectorXd kept = batch.environment(0).dofs();
  const BatchStepReport report = batch.step();
  EXPECT_EQ(report.stepped, 1);
  EXPECT_TRUE(batch.environment(0).dofs() == kept);
  EXPECT_DOUBLE_EQ(batch.environment(0).time(), 0.01);
  EXPECT_DOUBLE_EQ(batch.environment(1).time(), 0.02);
}

TEST(Batch, EnvironmentsOfOneModelShareItsStaticPartAndStartApart) {
  const std::shared_ptr<const Model> model = Model::build(rigid_slide());
  Batch batch(2);
  for (int i = 0; i < 4; ++i) {
    const int e = batch.add(model);
    // Each copy starts 2 cm further along y (across the ramp): the same motion, elsewhere.
    batch.environment(e).place(1, Eigen::Isometry3d(Eigen::Translation3d(0, 0.02 * i, 0)));
    batch.environment(e).place(0, Eigen::Isometry3d(Eigen::Translation3d(0, 0.02 * i, 0)));
  }
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(&batch.environment(i).model(), model.get());
    EXPECT_EQ(batch.environment(i).model().ordering().get(), model->ordering().get());
  }
  for (int s = 0; s < 10; ++s) batch.step();
  const Eigen::Vector3d first = batch.environment(0).center_of_mass(1);
  for (int i = 1; i < 4; ++i) {
    ASSERT_FALSE(batch.environment(i).failed()) << batch.environment(i).failure();
    const Eigen::Vector3d shift = batch.environment(i).center_of_mass(1) - first;
    EXPECT_NEAR(shift.y(), 0.02 * i, 1e-9);
    EXPECT_NEAR(shift.x(), 0.0, 1e-9);
    EXPECT_NEAR(shift.z(), 0.0, 1e-9);
  }
}

TEST(Environment, PlaceMovesABodyRigidly) {
  SceneDescription scene = soft_drop();
  scene.bodies.push_back(rigid_box("box", BodyType::kAffine, {0.02, 0.03, 0.04}, {0.1, 0, 0.1}));
  Environment env(Model::build(scene));
  const Eigen::Isometry3d motion = Eigen::Translation3d(0.01, -0.02, 0.03) *
                                   Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized());
  for (int body : {0, 1, 2}) {
    const Vertices before = env.body_vertices(body);
    env.place(body, motion);
    const Vertices after = env.body_vertices(body);
    for (Eigen::Index v = 0; v < before.rows(); ++v) {
      const Eigen::Vector3d expected = motion * Eigen::Vector3d(before.row(v));
      EXPECT_LT((Eigen::Vector3d(after.row(v)) - expected).norm(), 1e-12) << "body " << body;
    }
  }
  ASSERT_TRUE(env.step()) << env.failure();
  EXPECT_THROW(env.place(1, motion), std::logic_error);
}

}  // namespace
}  // namespace grip::solver::testing
