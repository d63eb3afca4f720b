// The data-parallel Newton iteration's bookkeeping (solver/parallel/newton_stages.hpp) on the
// host launchers, on the environments of tests/solver/parallel_step.hpp, against the CPU
// engine: each environment's free residual and right-hand side from its Newton system (the
// soft box on the affine box held, as a fixture holds it), the largest displacement a random
// step gives its vertices against the body kinds' max_displacement (FEM vertices inside the
// boxes included, affine bodies over their surface vertices), and a commit that moves only the
// environments that take their step.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "solver/batch/tbb_launcher.hpp"
#include "solver/parallel/launch.hpp"
#include "solver/parallel/newton_stages.hpp"
#include "solver/parallel/newton_system.hpp"
#include "tests/solver/parallel_step.hpp"

namespace grip::solver {
namespace {

using testing::append;
using testing::cpu_steps;
using testing::CpuStep;
using testing::moved;
using testing::parallel_step;
using testing::ParallelStep;
using testing::pointers;

// Per DOF whether it is fixed: the soft box on the affine box (body 3) held in every
// environment.
std::vector<char> held_soft_box(const std::vector<CpuStep>& steps) {
  std::vector<char> fixed;
  for (const CpuStep& c : steps) {
    const BodyModel& held = c.model->bodies()[3];
    for (int d = 0; d < c.model->dof_count(); ++d) {
      const bool in =
          d >= held.dof_offset && d < held.dof_offset + held.kind->dof_count(held.local);
      fixed.push_back(in || c.model->prescribed()[d] ? 1 : 0);
    }
  }
  return fixed;
}

TEST(ParallelNewton, ResidualAndRightHandSideAreTheCpuEnginesOverFreeDofs) {
  const std::vector<CpuStep> steps = cpu_steps();
  const ParallelStep s = parallel_step(pointers(steps));
  std::vector<double> q;
  const std::vector<Eigen::VectorXd> moved_q = moved(steps, 1e-4, 31);
  for (const Eigen::VectorXd& qe : moved_q) append(q, qe);
  const std::vector<char> fixed = held_soft_box(steps);
  parallel::SerialLauncher launch;
  const std::vector<double> gradient = testing::newton_system(s, q, launch).gradient;
  std::vector<double> rhs(q.size()), residual(steps.size());
  const std::vector<int>& dof_begin = s.collision.dof_begin();
  launch(static_cast<int>(q.size()),
         parallel::NewtonRightHandSideStage{fixed.data(), gradient.data(), nullptr, rhs.data()});
  launch(static_cast<int>(steps.size()),
         parallel::FreeResidualStage{dof_begin.data(), fixed.data(), gradient.data(),
                                     residual.data()});
  for (std::size_t e = 0; e < steps.size(); ++e) {
    const CpuStep& c = steps[e];
    const Vertices x = collision_positions(*c.model, moved_q[e], c.step.targets, 1.0);
    Eigen::VectorXd cpu;
    c.solver->potential().gradient(moved_q[e], x, *c.step.near, cpu);
    double cpu_residual = 0.0, held_largest = 0.0;
    for (Eigen::Index d = 0; d < cpu.size(); ++d) {
      const std::size_t at = dof_begin[e] + d;
      double& largest = fixed[at] ? held_largest : cpu_residual;
      largest = std::max(largest, std::abs(cpu[d]));
      EXPECT_EQ(rhs[at], fixed[at] ? 0.0 : -gradient[at]);
      EXPECT_NEAR(gradient[at], cpu[d], 1e-12 * cpu.lpNorm<Eigen::Infinity>());
    }
    EXPECT_NEAR(residual[e], cpu_residual, 1e-12 * cpu_residual) << "env " << e;
    EXPECT_GT(held_largest, 0.0);  // the held DOFs' forces were there to leave out
  }
}

// A random step of every DOF, and one of the affine bodies' alone (the FEM vertices' zero), so
// that each kind's displacement decides once.
TEST(ParallelNewton, StepLengthIsTheBodyKindsLargestDisplacement) {
  const std::vector<CpuStep> steps = cpu_steps();
  const ParallelStep s = parallel_step(pointers(steps));
  for (const bool affine_alone : {false, true}) {
    std::mt19937 random(32);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::vector<double> p(s.collision.dof_begin().back());
    for (double& x : p) x = 1e-3 * unit(random);
    if (affine_alone) {
      for (const int dof : s.fem.vertex_dof()) std::fill(&p[dof], &p[dof] + 3, 0.0);
    }
    std::vector<double> serial(steps.size()), tbb(steps.size());
    const auto stage = [&](double* out) {
      return parallel::StepDisplacementStage{s.fem.vertices(),
                                             s.fem.vertex_begin().data(),
                                             s.collision.vertices(),
                                             s.collision.vertex_begin().data(),
                                             p.data(),
                                             out};
    };
    parallel::SerialLauncher{}(static_cast<int>(steps.size()), stage(serial.data()));
    parallel::TbbLauncher{}(static_cast<int>(steps.size()), stage(tbb.data()));
    EXPECT_EQ(serial, tbb);
    for (std::size_t e = 0; e < steps.size(); ++e) {
      const Model& model = *steps[e].model;
      const Eigen::Map<const Eigen::VectorXd> dq(p.data() + s.collision.dof_begin()[e],
                                                 model.dof_count());
      double cpu = 0.0;
      for (const BodyModel& body : model.bodies()) {
        cpu = std::max(cpu, body.kind->max_displacement(body.local, dq));
      }
      EXPECT_GT(cpu, 0.0);
      EXPECT_EQ(serial[e], cpu) << "env " << e << (affine_alone ? ", affine bodies alone" : "");
    }
  }
}

TEST(ParallelNewton, CommitMovesOnlyTheEnvironmentsThatTakeTheirStep) {
  const std::vector<int> dof_begin{0, 4, 4, 10};  // the second environment has no DOFs
  std::vector<double> q(10, 1.0), p(10, 2.0);
  const std::vector<unsigned char> take{1, 1, 0};
  const std::vector<double> alpha{0.5, 0.25, 0.125};
  parallel::SerialLauncher{}(10, parallel::CommitStage{dof_begin.data(), 3, take.data(),
                                                       alpha.data(), p.data(), q.data()});
  for (int d = 0; d < 10; ++d) EXPECT_EQ(q[d], d < 4 ? 2.0 : 1.0) << d;
}

}  // namespace
}  // namespace grip::solver
