// The data-parallel Newton iteration (solver/parallel/newton_iteration.hpp) on the host
// launchers against the CPU engine's NewtonSolver::iterate, from the same start: the
// environments of tests/solver/parallel_step.hpp (damped soft boxes, an affine box and a driven
// cube within d_hat of a floor, a soft box on the affine box, random velocities), each step
// solved by both engines iteration by iteration.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "solver/batch/model_batch.hpp"
#include "solver/batch/tbb_launcher.hpp"
#include "solver/parallel/newton_iteration.hpp"
#include "tests/solver/parallel_step.hpp"

namespace grip::solver {
namespace {

using testing::append;
using testing::CpuStep;

// A batch and its iterate, begun from the CPU engine's steps.
struct ParallelRun {
  testing::ParallelStep s;
  parallel::SurfaceBatch surface;
  parallel::NewtonBatch batch;
  parallel::NewtonIterate it;

  explicit ParallelRun(const std::vector<const CpuStep*>& steps)
      : s(testing::parallel_step(steps)),
        surface(parallel::surface_batch(models(steps))),
        batch(s.fem, s.affine, s.collision, surface) {
    const std::vector<const Model*> m = models(steps);
    batch.prescribed = parallel::prescribed_dofs(m);
    batch.fixed = batch.prescribed;
    for (const CpuStep* c : steps) {
      const SimParameters& sim = c->model->sim();
      append(batch.prescribed_target, c->step.targets.prescribed_target);
      batch.d_hat.push_back(sim.d_hat);
      batch.kappa.push_back(c->state.kappa);
      batch.newton_tol.push_back(sim.newton_tol);
      batch.velocity_tol.push_back(sim.newton_velocity_tol);
      batch.standard_weight.push_back(c->step.standard_weight);
      batch.held.push_back(0);
      batch.projected_iterations.push_back(sim.projected_iterations);
    }
    it.step = s.step;
    it.step.progress.assign(steps.size(), 0.0);  // a step begins with its prescribed motion
    it.q = s.step.q_start;
    it.pairs = s.pairs;
    it.friction = s.friction;
    it.active.assign(steps.size(), 1);
    it.iteration.assign(steps.size(), 0);
    it.first_residual.assign(steps.size(), -1.0);
    it.convergence_expected.assign(steps.size(), 0);
  }

  static std::vector<const Model*> models(const std::vector<const CpuStep*>& steps) {
    std::vector<const Model*> out;
    for (const CpuStep* c : steps) out.push_back(c->model.get());
    return out;
  }
};

int outcome_of(NewtonSolver::Outcome o) {
  switch (o) {
    case NewtonSolver::Outcome::kContinue:
      return parallel::kNewtonContinue;
    case NewtonSolver::Outcome::kConverged:
      return parallel::kNewtonConverged;
    case NewtonSolver::Outcome::kFailed:
      break;
  }
  return parallel::kNewtonFailed;
}

// What the comparison found over a whole step.
struct Agreement {
  std::vector<int> iterations;         // per environment, until its solve stopped
  std::vector<int> last_outcome;       // per environment, its last iteration's
  std::vector<double> first_progress;  // per environment, after its first iteration
  // |q - q_cpu| over the step's largest |q - q_start|: the largest in any iteration, and the
  // largest where the solves stopped.
  double largest_difference = 0.0, final_difference = 0.0;
  std::vector<double> environment_largest;  // per environment, over its iterations
  std::vector<int> cg_iterations;           // per environment, over its iterations
};

template <class Launcher>
Agreement compare_steps(std::vector<CpuStep>& steps, Launcher&& launch, ParallelRun& run) {
  const std::vector<int>& dof_begin = run.s.collision.dof_begin();
  Agreement a;
  a.iterations.assign(steps.size(), 0);
  a.last_outcome.assign(steps.size(), parallel::kNewtonIdle);
  a.first_progress.assign(steps.size(), 0.0);
  a.environment_largest.assign(steps.size(), 0.0);
  a.cg_iterations.assign(steps.size(), 0);
  for (int iteration = 1; iteration <= 30; ++iteration) {
    parallel::newton_iteration(launch, run.batch, run.it);
    for (std::size_t e = 0; e < steps.size(); ++e) {
      if (run.it.active[e] == 0) continue;
      CpuStep& c = steps[e];
      StepDiagnostics diagnostics;
      NewtonSolver::FailureReport failure;
      const int cpu = outcome_of(c.solver->iterate(c.state, c.step, diagnostics, failure));
      EXPECT_EQ(run.it.outcome[e], cpu) << "environment " << e << ", iteration " << iteration;
      EXPECT_NEAR(run.it.step.progress[e], c.step.progress, 1e-6) << "environment " << e;
      double moved = 0.0, difference = 0.0;
      for (Eigen::Index d = 0; d < c.state.q.size(); ++d) {
        moved = std::max(moved, std::abs(c.state.q[d] - c.step.targets.q_start[d]));
        difference = std::max(difference, std::abs(run.it.q[dof_begin[e] + d] - c.state.q[d]));
      }
      a.largest_difference = std::max(a.largest_difference, difference / moved);
      a.environment_largest[e] = std::max(a.environment_largest[e], difference / moved);
      a.cg_iterations[e] += run.it.cg_iterations[e];
      a.iterations[e] = iteration;
      a.last_outcome[e] = run.it.outcome[e];
      if (iteration == 1) a.first_progress[e] = run.it.step.progress[e];
      if (cpu == parallel::kNewtonContinue) continue;
      run.it.active[e] = 0;
      a.final_difference = std::max(a.final_difference, difference / moved);
    }
    if (std::none_of(run.it.active.begin(), run.it.active.end(), [](auto x) { return x != 0; })) {
      break;
    }
  }
  return a;
}

// Each environment's iterations against the CPU engine's: the same outcome in each, the same
// progress, q within 1e-6 of the step's largest DOF change in every iteration (the CG's
// tolerance of 1e-10 against the CPU engine's direct solve; the first iteration's step, which
// carries the prescribed motion, differs most) and within 1e-9 where the solves stop, and every
// environment's solve converged in at least three iterations (the first takes the prescribed
// motion, so it neither converges nor searches for a decrease; later ones do).
Agreement expect_cpu_agreement(std::vector<CpuStep>& steps) {
  ParallelRun run(testing::pointers(steps));
  const Agreement a = compare_steps(steps, parallel::SerialLauncher{}, run);
  for (std::size_t e = 0; e < steps.size(); ++e) {
    EXPECT_EQ(a.last_outcome[e], parallel::kNewtonConverged) << "environment " << e;
    EXPECT_GE(a.iterations[e], 3) << "environment " << e;
  }
  EXPECT_LE(a.largest_difference, 1e-6);
  EXPECT_LE(a.final_difference, 1e-9);
  return a;
}

TEST(ParallelNewtonIteration, RestingStepsIterateAsTheCpuEngines) {
  std::vector<CpuStep> steps = testing::cpu_steps();
  expect_cpu_agreement(steps);
}

// The floor rising into the bodies and sliding under them, a pinned soft box carried sideways:
// iterations under prescribed motion, CCD and the force of the motion still to come.
TEST(ParallelNewtonIteration, StepsUnderPrescribedMotionIterateAsTheCpuEngines) {
  const auto near = Model::build(testing::moving_scene(4e-4, 1e-3, 0.01));
  const auto wide = Model::build(testing::moving_scene(1.2e-3, 2e-3, 0.005));
  std::vector<CpuStep> steps;
  steps.push_back(testing::begin_cpu_step(near, 21));
  steps.push_back(testing::begin_cpu_step(wide, 22));
  steps.push_back(testing::begin_cpu_step(near, 23));
  expect_cpu_agreement(steps);
}

// The floor rising ten times its gap in the step: in the wider scene CCD stops it about half
// way, and Newton makes room for the rest of its way over 20 iterations, the last ten with the
// contacts' Hessians exact (in five of them, 12 and 14 to 17, CG finds the exact matrix
// indefinite and solves the projected one instead, as the CPU engine's factorization refuses
// it) and one cut short by the line search.
TEST(ParallelNewtonIteration, StepsCutShortByCcdIterateAsTheCpuEngines) {
  const auto near = Model::build(testing::moving_scene(4e-4, 1e-3, 0.01, 10.0));
  const auto wide = Model::build(testing::moving_scene(1.2e-3, 2e-3, 0.005, 10.0));
  std::vector<CpuStep> steps;
  steps.push_back(testing::begin_cpu_step(near, 31));
  steps.push_back(testing::begin_cpu_step(wide, 32));
  steps.push_back(testing::begin_cpu_step(near, 33));
  const Agreement a = expect_cpu_agreement(steps);
  EXPECT_LT(a.first_progress[1], 0.6);
  EXPECT_GT(*std::max_element(a.iterations.begin(), a.iterations.end()), 12);
}

// Newton systems solved by dense Cholesky (each environment's ~190 DOFs) but the second
// environment's, by CG: the floor rising ten times its gap. A direct solve as the CPU engine's,
// so the dense environments' iterates agree within 1e-9 of the step's motion in every
// iteration (measured 2.2e-13), where CG's agree within 1e-6.
TEST(ParallelNewtonIteration, DenseCholeskyIteratesAsTheCpuEngines) {
  const auto near = Model::build(testing::moving_scene(4e-4, 1e-3, 0.01, 10.0));
  const auto wide = Model::build(testing::moving_scene(1.2e-3, 2e-3, 0.005, 10.0));
  std::vector<CpuStep> steps;
  for (int e = 0; e < 3; ++e)
    steps.push_back(testing::begin_cpu_step(e == 1 ? wide : near, 31 + e));
  ParallelRun run(testing::pointers(steps));
  run.batch.dense = {1, 0, 1};
  const Agreement a = compare_steps(steps, parallel::SerialLauncher{}, run);
  for (int e = 0; e < 3; ++e) {
    EXPECT_EQ(a.last_outcome[e], parallel::kNewtonConverged) << "environment " << e;
    EXPECT_LE(a.environment_largest[e], e == 1 ? 1e-6 : 1e-9) << "environment " << e;
    EXPECT_EQ(a.cg_iterations[e] > 0, e == 1) << "environment " << e;
  }
}

// The whole iteration's q, progress and outcomes: the serial and TBB launchers bit for bit, and
// an environment alone as in the batch.
struct Trajectory {
  std::vector<std::vector<double>> q;
  std::vector<std::vector<int>> outcome;
};

template <class Launcher>
Trajectory trajectory(const std::vector<const CpuStep*>& steps, Launcher&& launch) {
  ParallelRun run(steps);
  Trajectory t;
  for (int iteration = 0; iteration < 8; ++iteration) {
    parallel::newton_iteration(launch, run.batch, run.it);
    for (std::size_t e = 0; e < steps.size(); ++e) {
      if (run.it.outcome[e] != parallel::kNewtonContinue) run.it.active[e] = 0;
    }
    t.q.push_back(run.it.q);
    t.outcome.push_back(run.it.outcome);
  }
  return t;
}

TEST(ParallelNewtonIteration, LaunchersAgreeAndEnvironmentsAreIsolated) {
  const std::vector<CpuStep> steps = testing::cpu_steps();
  const std::vector<const CpuStep*> all = testing::pointers(steps);
  const Trajectory serial = trajectory(all, parallel::SerialLauncher{});
  const Trajectory threaded = trajectory(all, parallel::TbbLauncher(2));
  EXPECT_EQ(serial.q, threaded.q);
  EXPECT_EQ(serial.outcome, threaded.outcome);
  const Trajectory alone = trajectory({all[1]}, parallel::SerialLauncher{});
  const ParallelRun layout(all);
  const std::vector<int>& dof_begin = layout.s.collision.dof_begin();
  for (std::size_t i = 0; i < serial.q.size(); ++i) {
    const std::vector<double> second(serial.q[i].begin() + dof_begin[1],
                                     serial.q[i].begin() + dof_begin[2]);
    EXPECT_EQ(alone.q[i], second) << "iteration " << i + 1;
    EXPECT_EQ(alone.outcome[i][0], serial.outcome[i][1]) << "iteration " << i + 1;
  }
}

}  // namespace
}  // namespace grip::solver
