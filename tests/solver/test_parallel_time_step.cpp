// The data-parallel engine's whole time step (solver/batch/parallel_batch.hpp) on the host
// launchers against the CPU engine's Environment::step over several steps: the scenes of
// tests/solver/parallel_step.hpp under prescribed motion (a floor rising into damped soft
// boxes, an affine box and a driven cube and sliding under them, a soft box pinned to a mount
// carried sideways), each environment stepped by both engines from the same start.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "solver/batch/parallel_batch.hpp"
#include "solver/environment.hpp"
#include "tests/solver/parallel_step.hpp"

namespace grip::solver {
namespace {

using ModelPtr = std::shared_ptr<const Model>;

// What both engines did over a run of steps.
struct Comparison {
  // Per environment: |q - q_cpu| over the largest |q - q_0| so far, the largest over the steps.
  std::vector<double> difference;
  std::vector<int> cpu_iterations, parallel_iterations;  // over the steps
  std::vector<int> cpu_retries, parallel_retries;
  std::vector<Failure> cpu_failure, parallel_failure;
  std::vector<std::string> parallel_message;
  std::vector<double> cpu_time, parallel_time;
  std::vector<double> cpu_min_distance, parallel_min_distance;      // the last step's
  std::vector<double> cpu_volume, parallel_volume;                  // the last step's
  std::vector<std::vector<PairForce>> cpu_forces, parallel_forces;  // the last step's
  std::vector<long> cg_iterations;
};

Comparison compare(const std::vector<ModelPtr>& models, int steps, int threads = 1) {
  const std::size_t n = models.size();
  std::vector<Environment> cpu;
  std::vector<State> states;
  for (const ModelPtr& m : models) {
    cpu.emplace_back(m);
    states.push_back(cpu.back().state());
  }
  ParallelBatch batch(models, threads);
  Comparison c;
  c.difference.assign(n, 0.0);
  c.cpu_iterations.assign(n, 0);
  c.parallel_iterations.assign(n, 0);
  c.cpu_retries.assign(n, 0);
  c.parallel_retries.assign(n, 0);
  c.cpu_failure.assign(n, Failure::kNone);
  c.parallel_failure.assign(n, Failure::kNone);
  c.parallel_message.assign(n, "");
  c.cpu_time.assign(n, 0.0);
  c.parallel_time.assign(n, 0.0);
  c.cpu_min_distance.assign(n, 0.0);
  c.parallel_min_distance.assign(n, 0.0);
  c.cpu_volume.assign(n, 0.0);
  c.parallel_volume.assign(n, 0.0);
  c.cg_iterations.assign(n, 0);
  c.cpu_forces.resize(n);
  c.parallel_forces.resize(n);
  std::vector<double> moved(n, 0.0);
  std::vector<Eigen::VectorXd> q0;
  for (const State& s : states) q0.push_back(s.q);
  for (int step = 0; step < steps; ++step) {
    std::vector<unsigned char> stepping(n);
    for (std::size_t e = 0; e < n; ++e) stepping[e] = c.parallel_failure[e] == Failure::kNone;
    const std::vector<ParallelStepResult> results = batch.step(states, stepping);
    for (std::size_t e = 0; e < n; ++e) {
      if (stepping[e] == 0) continue;
      const ParallelStepResult& r = results[e];
      EXPECT_TRUE(r.stepped);
      c.parallel_failure[e] = r.failure;
      c.parallel_message[e] = r.message;
      c.parallel_iterations[e] += r.diagnostics.newton_iterations;
      c.parallel_retries[e] += r.diagnostics.retries;
      c.parallel_time[e] = states[e].time;
      c.parallel_min_distance[e] = r.diagnostics.min_distance;
      c.parallel_volume[e] = r.diagnostics.min_volume_ratio;
      c.parallel_forces[e] = r.diagnostics.contact_forces;
      c.cg_iterations[e] += r.cg_iterations;
      if (cpu[e].failed()) continue;
      cpu[e].step();
      c.cpu_failure[e] = cpu[e].failure_code();
      c.cpu_iterations[e] += cpu[e].last_step().newton_iterations;
      c.cpu_retries[e] += cpu[e].last_step().retries;
      c.cpu_time[e] = cpu[e].time();
      c.cpu_min_distance[e] = cpu[e].last_step().min_distance;
      c.cpu_volume[e] = cpu[e].last_step().min_volume_ratio;
      c.cpu_forces[e] = cpu[e].last_step().contact_forces;
      moved[e] = std::max(moved[e], (cpu[e].state().q - q0[e]).lpNorm<Eigen::Infinity>());
      const double difference = (states[e].q - cpu[e].state().q).lpNorm<Eigen::Infinity>();
      c.difference[e] = std::max(c.difference[e], difference / moved[e]);
    }
  }
  return c;
}

SceneDescription moving(double gap, double d_hat, double dt, double rise = 0.2) {
  SceneDescription scene = testing::moving_scene(gap, d_hat, dt, rise);
  // Every Newton system factorized afresh: the CPU engine solves directly, so that the engines
  // differ by CG's tolerance alone.
  scene.sim.reuse_iterations = 0;
  return scene;
}

// The last step's contact forces per pair of bodies: the same pairs, forces within 1e-9 of the
// largest.
void expect_same_forces(const std::vector<PairForce>& cpu, const std::vector<PairForce>& parallel) {
  ASSERT_EQ(parallel.size(), cpu.size());
  double largest = 0.0;
  for (const PairForce& f : cpu) largest = std::max({largest, f.force.norm(), f.normal_force});
  for (std::size_t k = 0; k < cpu.size(); ++k) {
    EXPECT_EQ(parallel[k].body_a, cpu[k].body_a);
    EXPECT_EQ(parallel[k].body_b, cpu[k].body_b);
    EXPECT_LE((parallel[k].force - cpu[k].force).norm(), 1e-9 * largest) << "pair " << k;
    EXPECT_NEAR(parallel[k].normal_force, cpu[k].normal_force, 1e-9 * largest) << "pair " << k;
  }
}

// Both engines stepped each environment alike: the same Newton iterations, retries, failures
// and clock; q within 1e-9 of the motion so far (CG to 1e-10 against direct solves); the
// closest contact and the worst tet within 1e-9 relative; the contact forces.
void expect_agreement(const Comparison& c) {
  for (std::size_t e = 0; e < c.difference.size(); ++e) {
    SCOPED_TRACE("environment " + std::to_string(e));
    EXPECT_LE(c.difference[e], 1e-9);
    EXPECT_EQ(c.parallel_iterations[e], c.cpu_iterations[e]);
    EXPECT_EQ(c.parallel_retries[e], c.cpu_retries[e]);
    EXPECT_EQ(c.parallel_failure[e], c.cpu_failure[e]);
    EXPECT_EQ(c.parallel_time[e], c.cpu_time[e]);
    if (std::isfinite(c.cpu_min_distance[e])) {
      EXPECT_NEAR(c.parallel_min_distance[e], c.cpu_min_distance[e], 1e-9 * c.cpu_min_distance[e]);
    } else {
      EXPECT_EQ(c.parallel_min_distance[e], c.cpu_min_distance[e]);
    }
    EXPECT_NEAR(c.parallel_volume[e], c.cpu_volume[e], 1e-9);
    if (c.cpu_failure[e] == Failure::kNone)
      expect_same_forces(c.cpu_forces[e], c.parallel_forces[e]);
  }
}

// Five steps of the floor rising and sliding under the bodies and the pinned box carried
// sideways, in three environments of two scenes: every step converges in 6 to 8 iterations;
// q within 1e-9 of the motion (measured at most 6.7e-11); CG takes about 42 iterations per
// Newton iteration.
TEST(ParallelTimeStep, StepsAsTheCpuEngine) {
  const auto near = Model::build(moving(4e-4, 1e-3, 0.01));
  const auto wide = Model::build(moving(1.2e-3, 2e-3, 0.005));
  const Comparison c = compare({near, wide, near}, 5);
  expect_agreement(c);
  for (std::size_t e = 0; e < 3; ++e) {
    EXPECT_EQ(c.parallel_failure[e], Failure::kNone);
    EXPECT_GE(c.parallel_iterations[e], 30);
    EXPECT_TRUE(std::isfinite(c.parallel_min_distance[e])) << "a contact within d_hat";
    EXPECT_GE(c.parallel_forces[e].size(), 3u) << "the floor, the soft box, the box, the link";
    EXPECT_GT(c.cg_iterations[e], 0);
  }
}

// Two friction lags per step: each converged solve is followed by a solve with friction lagged
// where the first ended (41 iterations over three steps, where one lag takes 21).
TEST(ParallelTimeStep, FurtherFrictionLagsAsTheCpuEngine) {
  SceneDescription scene = moving(4e-4, 1e-3, 0.01);
  scene.sim.friction_lag_iterations = 2;
  const Comparison c = compare({Model::build(scene)}, 3);
  expect_agreement(c);
  EXPECT_EQ(c.parallel_failure[0], Failure::kNone);
  EXPECT_GT(c.parallel_iterations[0], 35);
}

// Steps that need more Newton iterations than allowed, retried as halves, each part starting
// where the last ended: 0.08 s needing 8 iterations, allowed 7 and three halvings, fails at
// t = 0.04 s, half way, with the CPU engine's code after 35 iterations; 0.16 s (the floor
// rising twice as far) allowed 8 is retried twice, in shorter parts, and ends at 0.16 s
// exactly.
TEST(ParallelTimeStep, RetriesInHalvesAsTheCpuEngine) {
  SceneDescription scene = moving(4e-4, 1e-3, 0.08);
  scene.sim.max_newton_iters = 7;
  scene.sim.max_step_halvings = 3;
  const auto failing = Model::build(scene);
  scene.sim.dt = 0.16;
  scene.sim.max_newton_iters = 8;
  const auto halved = Model::build(scene);
  const Comparison c = compare({failing, halved}, 1);
  expect_agreement(c);
  EXPECT_EQ(c.parallel_failure[0], Failure::kNewtonLimit);
  EXPECT_EQ(c.parallel_retries[0], 3);
  EXPECT_EQ(c.parallel_time[0], 0.04);
  EXPECT_NE(c.parallel_message[0].find("in 7 iterations (after 3 halvings of dt)"),
            std::string::npos)
      << c.parallel_message[0];
  EXPECT_EQ(c.parallel_failure[1], Failure::kNone) << c.parallel_message[1];
  EXPECT_EQ(c.parallel_retries[1], 2);
  EXPECT_EQ(c.parallel_time[1], 0.16);
}

// The whole step's states: the serial and TBB launchers bit for bit; an environment alone as in
// the batch, while others lag their friction again or begin their step's parts anew in the
// middle of its solve (a step of 0.16 s that takes 9 iterations beside one of 0.01 s whose
// first lag converges in 7, and one of 0.16 s allowed 8 that is retried in halves, and fails
// in a later step); an environment left out of a step unchanged.
TEST(ParallelTimeStep, LaunchersAgreeAndEnvironmentsAreIsolated) {
  const auto near = Model::build(moving(4e-4, 1e-3, 0.01));
  const auto wide = Model::build(moving(4e-4, 1e-3, 0.16));
  SceneDescription scene = moving(4e-4, 1e-3, 0.01);
  scene.sim.friction_lag_iterations = 2;
  const auto lagged = Model::build(scene);
  scene = moving(4e-4, 1e-3, 0.16);
  scene.sim.max_newton_iters = 8;
  const auto retried = Model::build(scene);
  int retries = 0;  // the last environment's, in the last run
  const auto run = [&retries](const std::vector<ModelPtr>& models, int threads,
                              std::vector<unsigned char> stepping) {
    std::vector<State> states;
    for (const ModelPtr& m : models) states.push_back(Environment(m).state());
    ParallelBatch batch(models, threads);
    retries = 0;
    for (int step = 0; step < 3; ++step) {
      const std::vector<ParallelStepResult> results = batch.step(states, stepping);
      for (std::size_t e = 0; e < results.size(); ++e) {
        if (results[e].failure != Failure::kNone) stepping[e] = 0;  // it stays where it failed
      }
      retries += results.back().diagnostics.retries;
    }
    return states;
  };
  const std::vector<ModelPtr> models{near, wide, lagged, retried};
  const std::vector<State> serial = run(models, 1, {1, 1, 1, 1});
  EXPECT_GT(retries, 0);
  const std::vector<State> threaded = run(models, 2, {1, 1, 1, 1});
  const std::vector<State> left_out = run(models, 1, {1, 0, 1, 1});
  for (std::size_t e = 0; e < models.size(); ++e) {
    SCOPED_TRACE("environment " + std::to_string(e));
    EXPECT_EQ(serial[e].q, threaded[e].q);
    EXPECT_EQ(serial[e].v, threaded[e].v);
    const std::vector<State> alone = run({models[e]}, 1, {1});
    EXPECT_EQ(alone[0].q, serial[e].q);
    EXPECT_EQ(alone[0].time, serial[e].time);
  }
  EXPECT_EQ(left_out[0].q, serial[0].q);
  EXPECT_EQ(left_out[2].q, serial[2].q);
  EXPECT_EQ(left_out[1].q, Environment(wide).state().q);
  EXPECT_EQ(left_out[1].time, 0.0);
}

}  // namespace
}  // namespace grip::solver
