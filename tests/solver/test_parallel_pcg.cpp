// The data-parallel engine's per-environment linear solves (solver/parallel/block_pcg.hpp) on
// the host launchers, against the CPU engine's own: each environment's whole Newton matrix in
// blocks (tets, affine and driven bodies, masses, contact pairs made positive semi-definite),
// its pinned DOFs and a held FEM body fixed with prescribed values, solved by CG preconditioned
// by block Jacobi alone and with coarse levels of FEM aggregates, and compared with the CPU
// engine's elimination and sparse Cholesky (SparseAssembly, SparseCholesky). Also: the launchers
// agree bit for bit, an environment's solution and iteration count do not depend on its batch, and
// an indefinite environment or one that runs out of iterations stops alone, with its status,
// leaving the others as they would be.
#include <gtest/gtest.h>

#include <Eigen/Sparse>
#include <algorithm>
#include <random>
#include <set>
#include <vector>

#include "solver/batch/tbb_launcher.hpp"
#include "solver/linear/sparse_assembly.hpp"
#include "solver/linear/sparse_cholesky.hpp"
#include "solver/parallel/block_pcg.hpp"
#include "tests/solver/parallel_batch.hpp"

namespace grip::solver {
namespace {

using testing::Batch;

// A batch whose pairs' Hessians are positive semi-definite (H H^T / 12), as the barrier's
// projected ones are, so that every environment's matrix is positive definite.
Batch spd_batch(const std::vector<std::shared_ptr<const Model>>& models) {
  Batch b = testing::make_batch(models);
  for (std::size_t k = 0; k < b.pair_hessian.size() / 144; ++k) {
    Eigen::Map<Eigen::Matrix<double, 12, 12>> h(&b.pair_hessian[144 * k]);
    const Eigen::Matrix<double, 12, 12> psd = h * h.transpose() / 12.0;
    h = psd;
  }
  return b;
}

std::set<int> fem_vertex_units(const Batch& b) {
  std::set<int> units;
  for (const int dof : b.fem.vertex_dof()) units.insert(dof / 3);
  return units;
}

struct System {
  testing::Assembled matrix;
  std::vector<char> fixed;      // the models' pinned DOFs, and environment 1's first FEM body held
  std::vector<double> rhs, x0;  // fixed DOFs' values in x0, zeros elsewhere
};

System make_system(const Batch& b) {
  System s{testing::assemble_newton_matrix(b), {}, {}, {}};
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (std::size_t e = 0; e < b.models.size(); ++e) {
    const Model& model = *b.models[e];
    std::vector<char> fixed = model.prescribed();
    if (e == 1) {
      const BodyModel& held = model.bodies()[1];  // a soft box (testing::soft_scene)
      for (int d = held.dof_offset; d < held.dof_offset + held.dof_count; ++d) {
        fixed[d] = 1;
      }
    }
    s.fixed.insert(s.fixed.end(), fixed.begin(), fixed.end());
    for (int d = 0; d < model.dof_count(); ++d) {
      s.rhs.push_back(unit(random));
      s.x0.push_back(fixed[d] ? 1e-3 * unit(random) : 0.0);
    }
  }
  return s;
}

// The CPU engine's solution of environment e: the fixed DOFs' values moved to the right-hand
// side, their rows and columns left out, CHOLMOD on the rest.
Eigen::VectorXd cpu_solution(const Batch& b, const System& s, int e) {
  const int first = b.collision.dof_begin()[e], n = b.collision.dof_begin()[e + 1] - first;
  const Eigen::SparseMatrix<double> lower = testing::environment_lower(b, s.matrix, e);
  const std::vector<char> fixed(s.fixed.begin() + first, s.fixed.begin() + first + n);
  const Eigen::Map<const Eigen::VectorXd> lift(&s.x0[first], n);
  Eigen::VectorXd rhs = Eigen::Map<const Eigen::VectorXd>(&s.rhs[first], n);
  rhs -= lower.selfadjointView<Eigen::Lower>() * lift;
  for (int i = 0; i < n; ++i) {
    if (fixed[i]) rhs[i] = lift[i];
  }
  std::vector<Eigen::Triplet<double>> triplets;
  for (int k = 0; k < lower.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(lower, k); it; ++it) {
      triplets.emplace_back(static_cast<int>(it.row()), static_cast<int>(it.col()), it.value());
    }
  }
  SparseAssembly assembly;
  SparseCholesky cholesky;
  EXPECT_TRUE(cholesky.factorize(assembly.assemble(n, triplets, fixed)));
  return cholesky.solve(rhs);
}

struct Solved {
  std::vector<double> x;
  std::vector<int> status, iterations;
  std::vector<double> residual;
};

template <class Launcher>
Solved solve(const Batch& b, const System& s, Launcher&& launch, double tolerance = 1e-10,
             int max_iterations = 2000,
             int aggregate_vertices = parallel::kCoarseAggregateVertices) {
  parallel::HostPcg pcg(b.fem, b.affine, s.matrix.pattern, b.collision.dof_begin(),
                        aggregate_vertices);
  Solved out{s.x0, {}, {}, {}};
  pcg.solve(launch, s.matrix.blocks, s.fixed, s.rhs,
            std::vector<double>(b.models.size(), tolerance), max_iterations, out.x);
  out.status = pcg.status();
  out.iterations = pcg.iterations();
  out.residual = pcg.residual();
  return out;
}

// Environment e's solution against the CPU engine's, its fixed DOFs' values kept exactly.
void expect_cpu_solution(const Batch& b, const System& s, const Solved& pcg, int e) {
  EXPECT_EQ(pcg.status[e], parallel::kPcgConverged);
  EXPECT_GT(pcg.iterations[e], 0);
  EXPECT_LE(pcg.residual[e], 1e-10);
  const int first = b.collision.dof_begin()[e], n = b.collision.dof_begin()[e + 1] - first;
  const Eigen::VectorXd cpu = cpu_solution(b, s, e);
  const Eigen::Map<const Eigen::VectorXd> x(&pcg.x[first], n);
  EXPECT_LE((x - cpu).norm(), 1e-7 * cpu.norm());
  for (int i = 0; i < n; ++i) {
    if (s.fixed[first + i]) {
      EXPECT_EQ(x[i], s.x0[first + i]);
    }
  }
}

// With block Jacobi alone, and with coarse levels of small and of production aggregates.
TEST(ParallelPcg, SolvesEachEnvironmentAsTheCpuEnginesCholeskyDoes) {
  const Batch b =
      spd_batch({testing::mixed_scene(), testing::soft_scene(), testing::mixed_scene()});
  const System s = make_system(b);
  for (const int aggregate : {0, 2, parallel::kCoarseAggregateVertices}) {
    const Solved pcg = solve(b, s, parallel::SerialLauncher{}, 1e-10, 2000, aggregate);
    for (int e = 0; e < 3; ++e) {
      SCOPED_TRACE("aggregates of " + std::to_string(aggregate) + ", environment " +
                   std::to_string(e));
      expect_cpu_solution(b, s, pcg, e);
    }
  }
}

// The coarse level takes the soft scene's smooth errors: fewer iterations than block Jacobi
// alone, to the same tolerance.
TEST(ParallelPcg, TheCoarseLevelCutsIterations) {
  const Batch b = spd_batch({testing::soft_scene()});
  const System s = make_system(b);
  const Solved jacobi = solve(b, s, parallel::SerialLauncher{}, 1e-10, 2000, 0);
  const Solved two_level = solve(b, s, parallel::SerialLauncher{});
  ASSERT_EQ(jacobi.status[0], parallel::kPcgConverged);
  ASSERT_EQ(two_level.status[0], parallel::kPcgConverged);
  EXPECT_LT(2 * two_level.iterations[0], jacobi.iterations[0]);
}

// Every FEM vertex in one aggregate of at most the size asked, each aggregate a patch of
// vertices joined through shared tets within one environment, the aggregates in the order of
// their first units; affine bodies' units in none.
TEST(ParallelPcg, AggregatesArePatchesOfOneEnvironmentsMesh) {
  const Batch b =
      spd_batch({testing::mixed_scene(), testing::soft_scene(), testing::mixed_scene()});
  std::vector<int> unit_begin;
  for (const int dof : b.collision.dof_begin()) unit_begin.push_back(dof / 3);
  const int units = unit_begin.back(), size = 5;
  const parallel::CoarseSpace c = parallel::coarse_space(b.fem, size, units, unit_begin);
  const std::set<int> fem_units = fem_vertex_units(b);
  std::set<std::pair<int, int>> joined;  // units that share a tet
  const std::vector<int>& tets = b.fem.tet_dofs();
  for (std::size_t t = 0; t < tets.size(); t += 4) {
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) joined.insert({tets[t + i] / 3, tets[t + j] / 3});
    }
  }
  ASSERT_GT(c.aggregate_count(), 0);
  for (int g = 0; g < c.aggregate_count(); ++g) {
    const int begin = c.aggregate_unit_begin[g], end = c.aggregate_unit_begin[g + 1];
    ASSERT_GE(end - begin, 1);
    ASSERT_LE(end - begin, size);
    if (g > 0) {
      EXPECT_LT(c.aggregate_unit[c.aggregate_unit_begin[g - 1]], c.aggregate_unit[begin]);
    }
    const auto e = std::upper_bound(unit_begin.begin(), unit_begin.end(), c.aggregate_unit[begin]) -
                   unit_begin.begin() - 1;
    EXPECT_GE(g, c.aggregate_begin[e]);
    EXPECT_LT(g, c.aggregate_begin[e + 1]);
    std::set<int> reached{c.aggregate_unit[begin]};  // connected: grown from its first unit
    for (bool grew = true; grew;) {
      grew = false;
      for (int k = begin; k < end; ++k) {
        const int u = c.aggregate_unit[k];
        for (const int r : reached) {
          if (!reached.contains(u) && joined.contains({r, u})) {
            grew = reached.insert(u).second;
            break;
          }
        }
      }
    }
    EXPECT_EQ(static_cast<int>(reached.size()), end - begin);
  }
  for (int u = 0; u < units; ++u) {
    const int g = c.unit_aggregate[u];
    if (!fem_units.contains(u)) {
      EXPECT_EQ(g, -1);
      continue;
    }
    ASSERT_GE(g, 0);
    const auto first = c.aggregate_unit.begin() + c.aggregate_unit_begin[g];
    const auto last = c.aggregate_unit.begin() + c.aggregate_unit_begin[g + 1];
    EXPECT_EQ(std::count(first, last, u), 1);
  }
  EXPECT_EQ(c.aggregate_unit.size(), fem_units.size());
}

TEST(ParallelPcg, TbbAndSerialLaunchersAgreeBitForBit) {
  const Batch b =
      spd_batch({testing::mixed_scene(), testing::soft_scene(), testing::mixed_scene()});
  const System s = make_system(b);
  const Solved serial = solve(b, s, parallel::SerialLauncher{});
  const Solved threaded = solve(b, s, parallel::TbbLauncher(2));
  EXPECT_EQ(serial.x, threaded.x);
  EXPECT_EQ(serial.iterations, threaded.iterations);
}

// The serial launcher reading the running count every fifth iteration, as a GPU's reads it
// every poll_interval-th.
struct PollingLauncher : parallel::SerialLauncher {
  int poll_interval = 5;
};

TEST(ParallelPcg, ReadingTheRunningCountLessOftenChangesNothing) {
  const Batch b =
      spd_batch({testing::mixed_scene(), testing::soft_scene(), testing::mixed_scene()});
  const System s = make_system(b);
  for (const int aggregate : {0, parallel::kCoarseAggregateVertices}) {
    SCOPED_TRACE("aggregates of " + std::to_string(aggregate));
    const Solved every = solve(b, s, parallel::SerialLauncher{}, 1e-10, 2000, aggregate);
    const Solved fifth = solve(b, s, PollingLauncher{}, 1e-10, 2000, aggregate);
    // Environments that stop at different iterations, the last between two reads of the count,
    // so that the solve runs iterations after every environment has stopped.
    ASSERT_NE(every.iterations[0], every.iterations[1]);
    ASSERT_NE(*std::max_element(every.iterations.begin(), every.iterations.end()) % 5, 0);
    EXPECT_EQ(every.x, fifth.x);
    EXPECT_EQ(every.iterations, fifth.iterations);
    EXPECT_EQ(every.status, fifth.status);
    EXPECT_EQ(every.residual, fifth.residual);
  }
}

// Environment `e` of batch `of` against environment 0 of batch `alone`, bit for bit.
void expect_same_environment(const Batch& of, const Solved& in_batch, int e, const Batch& alone,
                             const Solved& solo) {
  const int first = of.collision.dof_begin()[e];
  ASSERT_EQ(alone.collision.dof_begin()[1], of.collision.dof_begin()[e + 1] - first);
  EXPECT_TRUE(std::equal(solo.x.begin(), solo.x.end(), in_batch.x.begin() + first));
  EXPECT_EQ(solo.iterations[0], in_batch.iterations[e]);
  EXPECT_EQ(solo.status[0], in_batch.status[e]);
}

TEST(ParallelPcg, AnEnvironmentsSolveDoesNotDependOnItsBatch) {
  const Batch three =
      spd_batch({testing::mixed_scene(), testing::soft_scene(), testing::mixed_scene()});
  const Batch alone = spd_batch({testing::mixed_scene()});
  const System s3 = make_system(three), s1 = make_system(alone);
  for (const int aggregate : {0, parallel::kCoarseAggregateVertices}) {
    SCOPED_TRACE("aggregates of " + std::to_string(aggregate));
    const Solved in_batch = solve(three, s3, parallel::SerialLauncher{}, 1e-10, 2000, aggregate);
    const Solved solo = solve(alone, s1, parallel::SerialLauncher{}, 1e-10, 2000, aggregate);
    // The two scenes take different iteration counts, so one froze while the other went on.
    ASSERT_NE(in_batch.iterations[0], in_batch.iterations[1]);
    expect_same_environment(three, in_batch, 0, alone, solo);
  }
}

TEST(ParallelPcg, AnIndefiniteEnvironmentStopsAloneWithItsStatus) {
  const Batch b =
      spd_batch({testing::mixed_scene(), testing::soft_scene(), testing::mixed_scene()});
  System s = make_system(b);
  const Solved clean = solve(b, s, parallel::SerialLauncher{});
  // Environment 1's coupling between FEM vertices made 1e4 times stronger: every DOF block's
  // diagonal block stays as it was (the preconditioner factors), but the matrix is indefinite.
  const std::set<int> fem_units = fem_vertex_units(b);
  for (int k = s.matrix.pattern.environment_begin[1]; k < s.matrix.pattern.environment_begin[2];
       ++k) {
    const int row = s.matrix.pattern.row[k], column = s.matrix.pattern.column[k];
    if (row == column || !fem_units.contains(row) || !fem_units.contains(column)) continue;
    for (int c = 0; c < 9; ++c) s.matrix.blocks[9 * k + c] *= 1e4;
  }
  // CG finds the direction of negative curvature where block Jacobi alone preconditions it;
  // the coarse level's Cholesky finds P^T A P indefinite before CG starts. Either stops it.
  EXPECT_EQ(solve(b, s, parallel::SerialLauncher{}, 1e-10, 2000, 0).status[1],
            parallel::kPcgIndefinite);
  const Solved broken = solve(b, s, parallel::SerialLauncher{});
  EXPECT_EQ(broken.status[1], parallel::kPcgBadPreconditioner);
  EXPECT_EQ(broken.iterations[1], 0);
  for (const int e : {0, 2}) {
    const int first = b.collision.dof_begin()[e], end = b.collision.dof_begin()[e + 1];
    EXPECT_EQ(broken.status[e], parallel::kPcgConverged);
    EXPECT_EQ(broken.iterations[e], clean.iterations[e]);
    EXPECT_TRUE(
        std::equal(broken.x.begin() + first, broken.x.begin() + end, clean.x.begin() + first));
  }
}

TEST(ParallelPcg, ANonPositiveDiagonalBlockFailsItsEnvironmentsPreconditioner) {
  const Batch b = spd_batch({testing::mixed_scene(), testing::soft_scene()});
  System s = make_system(b);
  int unit = -1;  // environment 1's first free FEM vertex
  for (const int u : fem_vertex_units(b)) {
    if (unit < 0 && 3 * u >= b.collision.dof_begin()[1] && !s.fixed[3 * u]) unit = u;
  }
  const int diagonal = s.matrix.pattern.diagonal_blocks({unit})[0];
  ASSERT_GE(diagonal, 0);
  s.matrix.blocks[9 * diagonal] = -1.0;
  const Solved broken = solve(b, s, parallel::SerialLauncher{});
  EXPECT_EQ(broken.status[0], parallel::kPcgConverged);
  EXPECT_EQ(broken.status[1], parallel::kPcgBadPreconditioner);
  EXPECT_EQ(broken.iterations[1], 0);
}

TEST(ParallelPcg, RunningOutOfIterationsIsSaid) {
  const Batch b = spd_batch({testing::mixed_scene(), testing::soft_scene()});
  const System s = make_system(b);
  const Solved clean = solve(b, s, parallel::SerialLauncher{});
  // The environment that takes more iterations is stopped one short of them.
  const int longer = clean.iterations[1] > clean.iterations[0] ? 1 : 0, shorter = 1 - longer;
  const int limit = clean.iterations[longer] - 1;
  ASSERT_GT(limit, clean.iterations[shorter]);
  const Solved limited = solve(b, s, parallel::SerialLauncher{}, 1e-10, limit);
  EXPECT_EQ(limited.status[shorter], parallel::kPcgConverged);
  EXPECT_EQ(limited.status[longer], parallel::kPcgIterationLimit);
  EXPECT_EQ(limited.iterations[longer], limit);
  EXPECT_GT(limited.residual[longer], 1e-10);
}

}  // namespace
}  // namespace grip::solver
