// The data-parallel engine behind the seam (solver/batch/parallel_engine.hpp): the same
// environments stepped through solver::Engine by it and by the CPU engine (solver::Batch),
// read through their handles between steps; environments joining, leaving and failing.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <vector>

#include "solver/batch/batch.hpp"
#include "solver/batch/parallel_engine.hpp"
#include "tests/solver/parallel_step.hpp"

namespace grip::solver {
namespace {

using ModelPtr = std::shared_ptr<const Model>;

SceneDescription moving(double gap, double d_hat, double dt) {
  SceneDescription scene = testing::moving_scene(gap, d_hat, dt);
  // Every Newton system factorized afresh: the CPU engine solves directly, so that the engines
  // differ by CG's tolerance alone.
  scene.sim.reuse_iterations = 0;
  return scene;
}

void add_all(Engine& engine, const std::vector<ModelPtr>& models) {
  for (const ModelPtr& m : models) engine.add(m);
}

// Rows of a and b within `tolerance` of b's largest row.
void expect_near_rows(const Vertices& a, const Vertices& b, double tolerance) {
  ASSERT_EQ(a.rows(), b.rows());
  const double largest = b.rowwise().norm().maxCoeff();
  EXPECT_GT(largest, 0.0);
  EXPECT_LE((a - b).rowwise().norm().maxCoeff(), tolerance * largest);
}

// Five steps of three environments under prescribed motion (tests/solver/parallel_step.hpp),
// one of them placed apart first, through the seam: the same Newton iterations, steps, clock and
// contact forces per pair of bodies as the CPU engine's; positions within 1e-9 of the motion;
// the contact forces on every collision vertex between steps (barrier and the last step's
// lagged friction) within 1e-9 of the largest, so the handle's potential is the step's.
TEST(ParallelEngine, StepsThroughTheSeamAsTheCpuEngine) {
  const auto near = Model::build(moving(4e-4, 1e-3, 0.01));
  const auto wide = Model::build(moving(1.2e-3, 2e-3, 0.005));
  Batch cpu(1);
  ParallelEngine parallel(1);
  for (Engine* engine : {static_cast<Engine*>(&cpu), static_cast<Engine*>(&parallel)}) {
    add_all(*engine, {near, wide, near});
    engine->environment(2).place(2, Eigen::Isometry3d(Eigen::Translation3d(0.01, 0.0, 0.0)));
  }
  for (int step = 0; step < 5; ++step) {
    const BatchStepReport a = cpu.step(), b = parallel.step();
    EXPECT_EQ(b.stepped, 3);
    EXPECT_EQ(b.failed, 0);
    EXPECT_EQ(b.iterations, a.iterations) << "step " << step;
    EXPECT_GE(b.rounds, 6);
    EXPECT_EQ(b.frozen, long(b.rounds) * 3 - b.iterations);
  }
  for (int e = 0; e < 3; ++e) {
    SCOPED_TRACE("environment " + std::to_string(e));
    const EnvironmentHandle& c = cpu.environment(e);
    EnvironmentHandle& p = parallel.environment(e);
    EXPECT_FALSE(p.failed());
    EXPECT_EQ(p.time(), c.time());
    EXPECT_EQ(p.statistics().steps, 5);
    EXPECT_EQ(p.statistics().newton_iterations, c.statistics().newton_iterations);
    EXPECT_EQ(p.statistics().steps_by_iterations, c.statistics().steps_by_iterations);
    EXPECT_GT(p.linear_solves().cg_iterations, 0);
    EXPECT_LE((p.dofs() - c.dofs()).lpNorm<Eigen::Infinity>(), 1e-9 * c.dofs().norm());
    EXPECT_EQ(p.last_step().contact_forces.size(), c.last_step().contact_forces.size());
    EXPECT_EQ(p.last_step().kappa, c.last_step().kappa);
    const VertexContactForces pf = p.vertex_contact_forces();
    const VertexContactForces cf = cpu.environment(e).vertex_contact_forces();
    expect_near_rows(pf.normal, cf.normal, 1e-9);
    expect_near_rows(pf.friction, cf.friction, 1e-9);
  }
}

// A start with two bodies crossing fails in the first step with the CPU engine's code, and
// stays failed; a step that runs out of Newton iterations and halvings fails with the CPU
// engine's code, message and retries; the third environment steps on.
TEST(ParallelEngine, FailsAsTheCpuEngine) {
  const auto near = Model::build(moving(4e-4, 1e-3, 0.01));
  SceneDescription scene = moving(4e-4, 1e-3, 0.08);
  scene.sim.max_newton_iters = 7;
  scene.sim.max_step_halvings = 3;
  const auto failing = Model::build(scene);
  Batch cpu(1);
  ParallelEngine parallel(1);
  for (Engine* engine : {static_cast<Engine*>(&cpu), static_cast<Engine*>(&parallel)}) {
    add_all(*engine, {near, failing, near});
    // The soft box (body 1) moved into the affine box (body 2): their tops in one plane.
    engine->environment(0).place(1, Eigen::Isometry3d(Eigen::Translation3d(-0.1, 0.0, 0.0)));
  }
  const BatchStepReport report = parallel.step();
  cpu.step();
  EXPECT_EQ(report.stepped, 3);
  EXPECT_EQ(report.failed, 2);
  for (int e = 0; e < 3; ++e) {
    SCOPED_TRACE("environment " + std::to_string(e));
    EXPECT_EQ(parallel.environment(e).failure_code(), cpu.environment(e).failure_code());
    EXPECT_EQ(parallel.environment(e).failure(), cpu.environment(e).failure());
    EXPECT_EQ(parallel.active(e), cpu.active(e));
  }
  EXPECT_EQ(parallel.environment(0).failure_code(), Failure::kIntersectingStart);
  EXPECT_EQ(parallel.environment(1).failure_code(), Failure::kNewtonLimit);
  EXPECT_EQ(parallel.environment(1).statistics().retries, 3);
  EXPECT_EQ(parallel.environment(1).time(), 0.04);
  EXPECT_EQ(parallel.environment(1).statistics().steps, 0);
  const Eigen::VectorXd failed_at = parallel.environment(0).dofs();
  EXPECT_EQ(parallel.step().stepped, 1);
  EXPECT_EQ(parallel.environment(0).dofs(), failed_at);
  EXPECT_EQ(parallel.environment(2).statistics().steps, 2);
}

// Environments that join after others have stepped, and leave before them, step bit for bit as
// they step alone on the engine (the batch is built again around them); a retired environment
// keeps its state.
TEST(ParallelEngine, EnvironmentsJoinAndLeaveBetweenSteps) {
  const auto near = Model::build(moving(4e-4, 1e-3, 0.01));
  const auto wide = Model::build(moving(1.2e-3, 2e-3, 0.005));
  ParallelEngine engine(2);
  engine.add(near);
  engine.step();
  engine.step();
  engine.add(wide);
  engine.step();
  engine.retire(0);
  EXPECT_FALSE(engine.active(0));
  const Eigen::VectorXd retired_at = engine.environment(0).dofs();
  engine.step();
  EXPECT_EQ(engine.environment(0).dofs(), retired_at);
  EXPECT_EQ(engine.environment(0).statistics().steps, 3);
  const auto alone = [](const ModelPtr& model, int steps) {
    ParallelEngine one(1);
    one.add(model);
    for (int s = 0; s < steps; ++s) one.step();
    return one.environment(0).state();
  };
  const State near_alone = alone(near, 3), wide_alone = alone(wide, 2);
  EXPECT_EQ(engine.environment(0).state().q, near_alone.q);
  EXPECT_EQ(engine.environment(0).state().v, near_alone.v);
  EXPECT_EQ(engine.environment(1).state().q, wide_alone.q);
  EXPECT_EQ(engine.environment(1).state().time, wide_alone.time);
}

// Steps held open (StepPolicy::freeze_converged off) are refused.
TEST(ParallelEngine, RefusesStepsHeldOpen) {
  ParallelEngine engine(1);
  engine.add(Model::build(moving(4e-4, 1e-3, 0.01)));
  engine.set_policy({.freeze_converged = false});
  EXPECT_THROW(engine.step(), std::invalid_argument);
}

}  // namespace
}  // namespace grip::solver
