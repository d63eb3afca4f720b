// The data-parallel Newton system while prescribed motion is still to come
// (solver/parallel/prescribed_motion_stages.hpp) on the host launchers, against the CPU engine:
// the environments of tests/solver/parallel_step.hpp with their floor rising a fifth of its gap
// in the step and the soft box on the affine box pinned at its top to a mount that moves
// sideways, taken at progress 0, 0.4 and 1 of the way. The force that the contacts' Hessians
// give the motion still to come equals the CPU engine's H_fk dk, and the Newton step solved
// from it (the pinned DOFs' motion kept, one soft box held), by CG and by dense Cholesky, is the
// CPU engine's elimination's.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <vector>

#include "solver/batch/model_batch.hpp"
#include "solver/batch/tbb_launcher.hpp"
#include "solver/parallel/block_pcg.hpp"
#include "solver/parallel/dense_cholesky.hpp"
#include "solver/parallel/newton_stages.hpp"
#include "solver/parallel/newton_system.hpp"
#include "solver/parallel/prescribed_motion_stages.hpp"
#include "tests/solver/parallel_step.hpp"

namespace grip::solver {
namespace {

using testing::append;
using testing::CpuStep;
using testing::parallel_step;
using testing::ParallelStep;
using testing::pointers;

struct Moving {
  std::vector<CpuStep> steps;
  std::vector<double> progress{0.0, 0.4, 1.0};
};

Moving moving_steps() {
  const auto near = Model::build(testing::moving_scene(4e-4, 1e-3, 0.01));
  const auto wide = Model::build(testing::moving_scene(1.2e-3, 2e-3, 0.005));
  Moving m;
  m.steps.push_back(testing::begin_cpu_step(near, 11));
  m.steps.push_back(testing::begin_cpu_step(wide, 12));
  m.steps.push_back(testing::begin_cpu_step(near, 13));
  return m;
}

// The CPU engine's Newton system at each environment's q and progress, with the force of the
// motion still to come (NewtonSolver::assemble).
struct CpuSystem {
  Eigen::VectorXd gradient, kinematic_force;
  Eigen::MatrixXd matrix;  // whole, symmetric
};

CpuSystem cpu_system(const CpuStep& c, const Eigen::VectorXd& q, double progress) {
  const Model& model = *c.model;
  const Vertices x = collision_positions(model, q, c.step.targets, progress);
  const Vertices motion = collision_positions(model, q, c.step.targets, 1.0) - x;
  CpuSystem s;
  std::vector<Eigen::Triplet<double>> triplets;
  c.solver->potential().derivatives(q, x, *c.step.near, s.gradient, triplets, &motion,
                                    &s.kinematic_force, true);
  s.matrix = Eigen::MatrixXd::Zero(q.size(), q.size());
  for (const auto& t : triplets) {
    s.matrix(t.row(), t.col()) += t.value();
    if (t.row() != t.col()) s.matrix(t.col(), t.row()) += t.value();
  }
  return s;
}

// The CPU engine's elimination: the fixed DOFs take `lift`, the free ones solve
// A_ff p_f = -g_f - f_f - A_fc lift_c.
Eigen::VectorXd cpu_newton_step(const CpuSystem& s, const std::vector<char>& fixed,
                                const Eigen::VectorXd& lift) {
  const Eigen::VectorXd rhs = -s.gradient - s.kinematic_force - s.matrix * lift;
  std::vector<int> free;
  for (int d = 0; d < static_cast<int>(fixed.size()); ++d) {
    if (fixed[d] == 0) free.push_back(d);
  }
  const int n = static_cast<int>(free.size());
  Eigen::MatrixXd a(n, n);
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) {
    b[i] = rhs[free[i]];
    for (int j = 0; j < n; ++j) a(i, j) = s.matrix(free[i], free[j]);
  }
  const Eigen::VectorXd p_free = a.ldlt().solve(b);
  Eigen::VectorXd p = lift;
  for (int i = 0; i < n; ++i) p[free[i]] = p_free[i];
  return p;
}

double largest(const Eigen::VectorXd& v) { return v.cwiseAbs().maxCoeff(); }

// Per DOF whether it is fixed: the pinned DOFs, and in the second environment the soft box
// (body 1) held.
std::vector<char> fixed_dofs(const Moving& m) {
  std::vector<char> fixed;
  for (std::size_t e = 0; e < m.steps.size(); ++e) {
    const Model& model = *m.steps[e].model;
    const BodyModel& held = model.bodies()[1];
    for (int d = 0; d < model.dof_count(); ++d) {
      const bool in =
          e == 1 && d >= held.dof_offset && d < held.dof_offset + held.kind->dof_count(held.local);
      fixed.push_back(in || model.prescribed()[d] ? 1 : 0);
    }
  }
  return fixed;
}

struct Batch {
  Moving m = moving_steps();
  ParallelStep s;
  std::vector<Eigen::VectorXd> q;
  std::vector<double> batch_q, prescribed_target;
  std::vector<const Model*> models;

  Batch() {
    s = parallel_step(pointers(m.steps));
    s.step.progress = m.progress;
    q = testing::moved(m.steps, 1e-5, 41);
    for (std::size_t e = 0; e < q.size(); ++e) {
      append(batch_q, q[e]);
      append(prescribed_target, m.steps[e].step.targets.prescribed_target);
      models.push_back(m.steps[e].model.get());
    }
  }
};

TEST(ParallelPrescribedMotion, KinematicForceIsTheCpuEnginesWhileMotionIsToCome) {
  const Batch batch;
  const parallel::NewtonSystem serial =
      testing::newton_system(batch.s, batch.batch_q, parallel::SerialLauncher{});
  const parallel::NewtonSystem threaded =
      testing::newton_system(batch.s, batch.batch_q, parallel::TbbLauncher(2));
  EXPECT_EQ(serial.force, threaded.force);
  const std::vector<int>& dof_begin = batch.s.collision.dof_begin();
  for (std::size_t e = 0; e < batch.q.size(); ++e) {
    const CpuSystem cpu = cpu_system(batch.m.steps[e], batch.q[e], batch.m.progress[e]);
    const double scale = largest(cpu.kinematic_force);
    if (batch.m.progress[e] < 1.0) {
      // The rising floor presses on the bodies within d_hat of it.
      EXPECT_GT(scale, 1e-3 * largest(cpu.gradient)) << "environment " << e;
    } else {
      EXPECT_EQ(scale, 0.0) << "environment " << e;
    }
    double difference = 0.0;
    for (Eigen::Index d = 0; d < cpu.kinematic_force.size(); ++d) {
      difference =
          std::max(difference, std::abs(serial.force[dof_begin[e] + d] - cpu.kinematic_force[d]));
    }
    EXPECT_LE(difference, 1e-12 * std::max(scale, 1e-300)) << "environment " << e;
  }
}

// The batch's right-hand side and fixed DOFs' values (the solve's x on entry).
struct RightHandSide {
  std::vector<char> fixed;
  std::vector<double> rhs, x;
};

template <class Launcher>
RightHandSide right_hand_side(const Batch& batch, const parallel::NewtonSystem& system,
                              Launcher& launch) {
  RightHandSide r{fixed_dofs(batch.m), {}, {}};
  const std::vector<char> prescribed = parallel::prescribed_dofs(batch.models);
  const std::vector<int>& dof_begin = batch.s.collision.dof_begin();
  const int dofs = static_cast<int>(batch.batch_q.size());
  r.rhs.resize(dofs);
  r.x.resize(dofs);
  launch(dofs, parallel::NewtonRightHandSideStage{r.fixed.data(), system.gradient.data(),
                                                  system.force.data(), r.rhs.data()});
  launch(dofs, parallel::FixedMotionStage{dof_begin.data(), static_cast<int>(batch.q.size()),
                                          batch.s.step.progress.data(), prescribed.data(),
                                          batch.prescribed_target.data(), batch.batch_q.data(),
                                          r.x.data()});
  return r;
}

// Every environment's Newton step by dense Cholesky (dense_cholesky.hpp), with its status.
struct DenseSolve {
  std::vector<double> x;
  std::vector<int> status;
};

template <class Launcher>
DenseSolve dense_solve(const Batch& batch, const parallel::NewtonSystem& system,
                       const RightHandSide& r, Launcher&& launch) {
  const std::vector<int>& dof_begin = batch.s.collision.dof_begin();
  const parallel::BlockPattern& pattern = system.structure.pattern;
  const std::vector<long long> matrix_begin = parallel::dense_matrix_begin(dof_begin);
  std::vector<double> matrix(static_cast<std::size_t>(matrix_begin.back()));
  DenseSolve out{r.x, std::vector<int>(batch.q.size())};
  launch(static_cast<int>(batch.q.size()),
         parallel::DenseCholeskyStage{
             {static_cast<int>(batch.q.size()), dof_begin.data(), pattern.environment_begin.data(),
              pattern.row.data(), pattern.column.data(), system.blocks.data(), r.fixed.data(),
              r.rhs.data(), matrix_begin.data(), matrix.data(), out.x.data(), out.status.data()}});
  return out;
}

// The CPU engine's step of environment e: its elimination solved directly.
Eigen::VectorXd cpu_step(const Batch& batch, const std::vector<char>& fixed, int e) {
  const CpuStep& c = batch.m.steps[e];
  const double progress = batch.m.progress[e];
  const std::vector<int>& dof_begin = batch.s.collision.dof_begin();
  const int n = c.model->dof_count();
  const std::vector<char> env_fixed(fixed.begin() + dof_begin[e], fixed.begin() + dof_begin[e + 1]);
  Eigen::VectorXd lift = Eigen::VectorXd::Zero(n);
  for (int d = 0; d < n; ++d) {
    if (c.model->prescribed()[d] && progress < 1.0) {
      lift[d] = c.step.targets.prescribed_target[d] - batch.q[e][d];
    }
  }
  // The mount moves 0.1 mm (0.05 mm) in the step: the pinned DOFs' motion is the lift.
  EXPECT_EQ(largest(lift) > 1e-5, progress < 1.0) << "environment " << e;
  return cpu_newton_step(cpu_system(c, batch.q[e], progress), env_fixed, lift);
}

// Environment e's solution in x against the CPU engine's p: the fixed DOFs' values exactly,
// the whole within `tolerance` relative.
void expect_step(const std::vector<double>& x, const Eigen::VectorXd& p, const Batch& batch,
                 const std::vector<char>& fixed, int e, double tolerance) {
  const int first = batch.s.collision.dof_begin()[e];
  double difference = 0.0;
  for (Eigen::Index d = 0; d < p.size(); ++d) {
    if (fixed[first + d]) {
      EXPECT_EQ(x[first + d], p[d]) << "environment " << e;
    }
    difference = std::max(difference, std::abs(x[first + d] - p[d]));
  }
  EXPECT_LE(difference, tolerance * largest(p)) << "environment " << e;
}

// By CG to 1e-12 (within 1e-7) and by dense Cholesky (within 1e-10: a direct solve, as the CPU
// engine's).
TEST(ParallelPrescribedMotion, NewtonStepIsTheCpuEnginesElimination) {
  const Batch batch;
  parallel::SerialLauncher launch;
  const parallel::NewtonSystem system = testing::newton_system(batch.s, batch.batch_q, launch);
  const RightHandSide r = right_hand_side(batch, system, launch);
  const std::vector<int>& dof_begin = batch.s.collision.dof_begin();
  const int environments = static_cast<int>(batch.q.size());
  std::vector<double> x = r.x;
  parallel::HostPcg pcg(batch.s.fem, batch.s.affine, system.structure.pattern, dof_begin);
  pcg.solve(launch, system.blocks, r.fixed, r.rhs, std::vector<double>(environments, 1e-12), 2000,
            x);
  const DenseSolve dense = dense_solve(batch, system, r, launch);
  for (int e = 0; e < environments; ++e) {
    ASSERT_EQ(pcg.status()[e], parallel::kPcgConverged) << "environment " << e;
    ASSERT_EQ(dense.status[e], parallel::kDenseSolved) << "environment " << e;
    const Eigen::VectorXd p = cpu_step(batch, r.fixed, e);
    expect_step(x, p, batch, r.fixed, e, 1e-7);
    expect_step(dense.x, p, batch, r.fixed, e, 1e-10);
  }
}

// Serial and TBB alike, an environment alone as in the batch (its values and its neighbours'
// untouched), and an environment whose matrix is not positive definite (a diagonal entry
// negated) reported so, the others solved as before.
TEST(ParallelPrescribedMotion, DenseCholeskyIsolatesEnvironments) {
  const Batch batch;
  parallel::SerialLauncher launch;
  parallel::NewtonSystem system = testing::newton_system(batch.s, batch.batch_q, launch);
  const RightHandSide r = right_hand_side(batch, system, launch);
  const DenseSolve serial = dense_solve(batch, system, r, launch);
  EXPECT_EQ(serial.x, dense_solve(batch, system, r, parallel::TbbLauncher(2)).x);
  // A free DOF's diagonal entry in the second environment (its first body is held).
  const parallel::BlockPattern& pattern = system.structure.pattern;
  int block = pattern.environment_begin[2] - 1;
  while (pattern.row[block] != pattern.column[block] || r.fixed[3 * pattern.row[block]] != 0) {
    --block;
  }
  ASSERT_GE(block, pattern.environment_begin[1]);
  system.blocks[9 * block] = -1.0;
  const DenseSolve with_broken = dense_solve(batch, system, r, launch);
  EXPECT_EQ(with_broken.status,
            (std::vector<int>{parallel::kDenseSolved, parallel::kDenseNotPositiveDefinite,
                              parallel::kDenseSolved}));
  const std::vector<int>& dof_begin = batch.s.collision.dof_begin();
  for (int e : {0, 2}) {
    for (int d = dof_begin[e]; d < dof_begin[e + 1]; ++d) {
      ASSERT_EQ(with_broken.x[d], serial.x[d]) << "environment " << e;
    }
  }
}

TEST(ParallelPrescribedMotion, ProgressAdvancesByTheTakenFractionOfTheWayLeft) {
  const std::vector<unsigned char> take{1, 1, 0, 1};
  const std::vector<double> alpha{0.5, 1.0, 0.5, 0.25};
  std::vector<double> progress{0.4, 0.4, 0.4, 0.0};
  parallel::SerialLauncher launch;
  launch(4, parallel::ProgressStage{take.data(), alpha.data(), progress.data()});
  EXPECT_EQ(progress, (std::vector<double>{0.4 + 0.5 * 0.6, 1.0, 0.4, 0.25}));
}

}  // namespace
}  // namespace grip::solver
