// The data-parallel engine's barrier stage (solver/parallel/contact_stages.hpp) on the host
// launchers against the CPU engine's per-contact values (BarrierTerm: kernels::contact_barrier,
// its Hessian projected by Eigen's eigen-solver), over a batch of three environments with
// different d_hat and kappa: point-triangle pairs and edge pairs at 5 % to 120 % of d_hat,
// nearly parallel edges (mollified) among them.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "solver/batch/tbb_launcher.hpp"
#include "solver/kernels/psd_projection.hpp"
#include "solver/parallel/contact_stages.hpp"
#include "solver/parallel/launch.hpp"

namespace grip::solver {
namespace {

using parallel::BarrierStage;
using parallel::ContactPairs;
using Vector12 = Eigen::Matrix<double, 12, 1>;
using Matrix12 = Eigen::Matrix<double, 12, 12>;

constexpr int kPairsPerEnvironment = 400;

struct Batch {
  ContactPairs pairs;
  std::vector<double> positions;  // 3 per collision vertex, every environment's
};

Eigen::Vector3d random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  return Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
}

// Four vertices of a pair whose distance is `distance`: a point above a triangle's interior,
// or two edges crossing at an angle (nearly parallel for a small one).
std::array<Eigen::Vector3d, 4> pair_vertices(bool edge_edge, double distance, double angle,
                                             std::mt19937_64& rng) {
  const Eigen::Vector3d n = random_unit(rng);
  const Eigen::Vector3d u = n.unitOrthogonal(), w = n.cross(u);
  const Eigen::Vector3d origin = 0.01 * random_unit(rng);
  if (!edge_edge) {
    return {origin + distance * n, origin - 0.004 * u - 0.003 * w, origin + 0.005 * u - 0.002 * w,
            origin + 0.004 * w};
  }
  const Eigen::Vector3d b = std::cos(angle) * u + std::sin(angle) * w;
  return {origin - 0.006 * u, origin + 0.006 * u, origin + distance * n - 0.005 * b,
          origin + distance * n + 0.005 * b};
}

Batch make_batch(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> fraction(0.05, 1.2);
  Batch batch;
  const double d_hats[3] = {1e-3, 5e-4, 2e-3}, kappas[3] = {3e6, 1e5, 1e7};
  for (int e = 0; e < 3; ++e) {
    batch.pairs.begin_environment(4 * kPairsPerEnvironment, d_hats[e], kappas[e]);
    for (int k = 0; k < kPairsPerEnvironment; ++k) {
      const bool edge_edge = k % 2 == 1;
      const double angle =
          k % 6 == 1 ? 1e-3 : 0.3 + k % 5 * 0.2;  // every third edge pair nearly parallel
      const auto x = pair_vertices(edge_edge, fraction(rng) * d_hats[e], angle, rng);
      for (const Eigen::Vector3d& v : x)
        batch.positions.insert(batch.positions.end(), {v.x(), v.y(), v.z()});
      const int vertex[4] = {4 * k, 4 * k + 1, 4 * k + 2, 4 * k + 3};
      // The threshold as the CPU engine sets it from the rest lengths (here: these positions).
      const double eps = kernels::edge_edge_mollifier_threshold(x[0], x[1], x[2], x[3]);
      batch.pairs.add(edge_edge, vertex, eps);
    }
  }
  return batch;
}

struct Values {
  std::vector<double> energy, gradient, hessian;
};

template <class Launcher>
Values run_stage(const Batch& b, Launcher&& launch) {
  const int n = b.pairs.pairs().count;
  Values v{std::vector<double>(n), std::vector<double>(12 * std::size_t(n)),
           std::vector<double>(144 * std::size_t(n))};
  launch(n, BarrierStage{b.pairs.pairs(), b.positions.data(), nullptr, v.energy.data(),
                         v.gradient.data(), v.hessian.data()});
  return v;
}

TEST(ParallelBarrier, MatchesTheCpuEnginesContactValues) {
  const Batch b = make_batch(1);
  const Values v = run_stage(b, parallel::SerialLauncher{});
  int active = 0, mollified = 0, projected = 0;
  double worst_hessian = 0.0;
  for (int k = 0; k < b.pairs.pairs().count; ++k) {
    Eigen::Vector3d x[4];
    for (int c = 0; c < 4; ++c) {
      x[c] = Eigen::Map<const Eigen::Vector3d>(&b.positions[3 * b.pairs.vertex()[4 * k + c]]);
    }
    const int e = b.pairs.environment()[k];
    const bool edge_edge = b.pairs.edge_edge()[k] != 0;
    const kernels::ContactBarrier cpu = kernels::contact_barrier(
        edge_edge, b.pairs.mollifier_eps()[k], x, b.pairs.d_hat()[e], b.pairs.kappa()[e], true);
    ASSERT_EQ(v.energy[k], cpu.value) << "pair " << k;
    ASSERT_TRUE(Eigen::Map<const Vector12>(&v.gradient[12 * k]) == cpu.gradient) << "pair " << k;
    const Matrix12 host = kernels::project_to_psd<12>(cpu.hessian);
    const Eigen::Map<const Matrix12> stage(&v.hessian[144 * k]);
    if (cpu.value > 0.0) {
      ++active;
      worst_hessian = std::max(worst_hessian, (stage - host).norm() / host.norm());
    }
    projected += host != cpu.hessian;
    mollified +=
        edge_edge && cpu.value > 0.0 &&
        kernels::edge_edge_mollifier(x[0], x[1], x[2], x[3], b.pairs.mollifier_eps()[k]) < 1.0;
  }
  EXPECT_LE(worst_hessian, 1e-12);
  // The batch covers what it should: pairs beyond d_hat, mollified edges, projected Hessians.
  EXPECT_GT(active, 600);
  EXPECT_LT(active, b.pairs.pairs().count);
  EXPECT_GT(mollified, 20);
  EXPECT_GT(projected, 100);
  std::cout << active << " pairs within d_hat, " << mollified << " mollified, " << projected
            << " projected; largest Hessian difference " << worst_hessian << "\n";
}

TEST(ParallelBarrier, TbbAndSerialLaunchersAgreeBitForBit) {
  const Batch b = make_batch(2);
  const Values serial = run_stage(b, parallel::SerialLauncher{});
  const Values threaded = run_stage(b, parallel::TbbLauncher(2));
  EXPECT_EQ(serial.energy, threaded.energy);
  EXPECT_EQ(serial.gradient, threaded.gradient);
  EXPECT_EQ(serial.hessian, threaded.hessian);
}

TEST(ParallelBarrier, PairsAreNumberedPerEnvironment) {
  const Batch b = make_batch(3);
  EXPECT_EQ(b.pairs.vertex_begin()[2], 8 * kPairsPerEnvironment);
  EXPECT_EQ(b.pairs.pair_begin()[3], 3 * kPairsPerEnvironment);
  EXPECT_EQ(b.pairs.vertex()[4 * kPairsPerEnvironment], 4 * kPairsPerEnvironment);
  EXPECT_EQ(b.pairs.environment().back(), 2);
}

}  // namespace
}  // namespace grip::solver
