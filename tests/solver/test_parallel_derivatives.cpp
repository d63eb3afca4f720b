// The data-parallel engine's Newton system (solver/parallel/derivative_stages.hpp) on the host
// launchers against the CPU engine's IncrementalPotential::derivatives, on the environments of
// tests/solver/parallel_step.hpp, where every term acts: each environment's gradient and its
// Newton matrix's lower triangle at the step's start and at moved points, the gradient against
// central differences of the data-parallel energy, serial and TBB launchers alike, and an
// environment the same alone as in the batch.
#include <gtest/gtest.h>

#include <Eigen/Sparse>
#include <cmath>
#include <random>
#include <vector>

#include "solver/batch/tbb_launcher.hpp"
#include "solver/parallel/launch.hpp"
#include "solver/parallel/newton_system.hpp"
#include "solver/parallel/potential_arrays.hpp"
#include "tests/solver/parallel_batch.hpp"
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

std::vector<double> flat(const std::vector<Eigen::VectorXd>& q) {
  std::vector<double> out;
  for (const Eigen::VectorXd& qe : q) append(out, qe);
  return out;
}

// Environment e's Newton matrix, its lower triangle over its own DOFs.
Eigen::SparseMatrix<double> lower(const parallel::NewtonSystem& d,
                                  const std::vector<int>& dof_begin, int e) {
  return testing::lower_triangle(d.structure.pattern, d.blocks, dof_begin, e);
}

struct CpuDerivatives {
  Eigen::VectorXd gradient;
  Eigen::SparseMatrix<double> lower;
};

CpuDerivatives cpu_derivatives(const CpuStep& c, const Eigen::VectorXd& q) {
  const Vertices x = collision_positions(*c.model, q, c.step.targets, 1.0);
  CpuDerivatives out;
  Triplets triplets;
  c.solver->potential().derivatives(q, x, *c.step.near, out.gradient, triplets);
  out.lower.resize(q.size(), q.size());
  out.lower.setFromTriplets(triplets.begin(), triplets.end());
  return out;
}

double largest(const Eigen::SparseMatrix<double>& m) {
  double most = 0.0;
  for (int k = 0; k < m.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(m, k); it; ++it) {
      most = std::max(most, std::abs(it.value()));
    }
  }
  return most;
}

TEST(ParallelDerivatives, GradientAndNewtonMatrixMatchTheCpuEngines) {
  const std::vector<CpuStep> steps = cpu_steps();
  const ParallelStep s = parallel_step(pointers(steps));
  const std::vector<int>& dof_begin = s.collision.dof_begin();
  for (const double reach : {0.0, 1e-4}) {
    const std::vector<Eigen::VectorXd> q = moved(steps, reach, 21);
    const parallel::NewtonSystem d = testing::newton_system(s, flat(q), parallel::SerialLauncher{});
    const parallel::NewtonSystem tbb = testing::newton_system(s, flat(q), parallel::TbbLauncher{});
    EXPECT_EQ(d.gradient, tbb.gradient);
    EXPECT_EQ(d.blocks, tbb.blocks);
    for (int e = 0; e < 3; ++e) {
      const CpuDerivatives cpu = cpu_derivatives(steps[e], q[e]);
      const Eigen::Map<const Eigen::VectorXd> g(d.gradient.data() + dof_begin[e], q[e].size());
      const double scale = cpu.gradient.lpNorm<Eigen::Infinity>();
      EXPECT_LE((g - cpu.gradient).lpNorm<Eigen::Infinity>(), 1e-12 * scale)
          << "reach " << reach << " env " << e;
      const Eigen::SparseMatrix<double> h = lower(d, dof_begin, e);
      EXPECT_LE(largest(h - cpu.lower), 1e-12 * largest(cpu.lower))
          << "reach " << reach << " env " << e;
    }
  }
}

// g.d against (E(q + eps d) - E(q - eps d)) / (2 eps), both the data-parallel engine's, along
// random directions: the h^2 scaling and every gather are the energy's own.
TEST(ParallelDerivatives, GradientIsTheEnergysSlope) {
  const std::vector<CpuStep> steps = cpu_steps();
  const ParallelStep s = parallel_step(pointers(steps));
  const std::vector<double> q = flat(moved(steps, 1e-4, 22));
  const parallel::NewtonSystem d = testing::newton_system(s, q, parallel::SerialLauncher{});
  const auto arrays = s.arrays();
  const parallel::PotentialBuffers b = arrays.buffers();
  parallel::PotentialStorage<parallel::HostArray> work(b);
  parallel::SerialLauncher launch;
  const auto energies = [&](const std::vector<double>& at) {
    std::vector<double> e(3);
    parallel::incremental_potential(launch, b, at.data(), work.work(), e.data());
    return e;
  };
  std::mt19937 random(23);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 3; ++trial) {
    std::vector<double> direction(q.size()), plus = q, minus = q;
    const double eps = 1e-7;
    for (std::size_t k = 0; k < q.size(); ++k) {
      direction[k] = 1e-3 * unit(random);
      plus[k] += eps * direction[k];
      minus[k] -= eps * direction[k];
    }
    const std::vector<double> up = energies(plus), down = energies(minus);
    const std::vector<int>& dof_begin = s.collision.dof_begin();
    for (int e = 0; e < 3; ++e) {
      double slope = 0.0;
      for (int k = dof_begin[e]; k < dof_begin[e + 1]; ++k) slope += d.gradient[k] * direction[k];
      const double difference = (up[e] - down[e]) / (2.0 * eps);
      EXPECT_NEAR(slope, difference, 1e-5 * std::abs(slope)) << "trial " << trial << " env " << e;
    }
  }
}

// Each environment's gradient and matrix the same, bit for bit, alone as in the batch.
TEST(ParallelDerivatives, AnEnvironmentIsTheSameAloneAsInTheBatch) {
  const std::vector<CpuStep> steps = cpu_steps();
  const ParallelStep together = parallel_step(pointers(steps));
  const std::vector<Eigen::VectorXd> q = moved(steps, 1e-4, 24);
  const parallel::NewtonSystem all =
      testing::newton_system(together, flat(q), parallel::SerialLauncher{});
  const std::vector<int>& dof_begin = together.collision.dof_begin();
  for (int e = 0; e < 3; ++e) {
    const ParallelStep alone = parallel_step({&steps[e]});
    const parallel::NewtonSystem one =
        testing::newton_system(alone, flat({q[e]}), parallel::SerialLauncher{});
    const std::vector<double> part(all.gradient.begin() + dof_begin[e],
                                   all.gradient.begin() + dof_begin[e + 1]);
    EXPECT_EQ(one.gradient, part) << "env " << e;
    const Eigen::SparseMatrix<double> a = lower(one, alone.collision.dof_begin(), 0),
                                      b = lower(all, dof_begin, e);
    EXPECT_EQ(largest(a - b), 0.0) << "env " << e;
  }
}

}  // namespace
}  // namespace grip::solver
