// The data-parallel engine's friction stage (solver/parallel/friction_stages.hpp) on the host
// launchers, over a batch of three environments with different eps_v h: point-triangle and
// edge-edge contacts whose tangential slides over the step run from a tenth of eps (static
// friction) to ten times it (sliding). Against the CPU engine's per-contact values (FrictionTerm:
// kernels::friction_potential and its derivatives) bit for bit; the gradient against central
// differences of the energy; the Hessian positive semi-definite; a sliding point pushed back
// by mu lambda against its slide.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <iostream>
#include <random>
#include <vector>

#include "solver/batch/tbb_launcher.hpp"
#include "solver/kernels/relative_velocity.hpp"
#include "solver/parallel/friction_stages.hpp"
#include "solver/parallel/launch.hpp"

namespace grip::solver {
namespace {

using parallel::FrictionContacts;
using parallel::FrictionStage;
using Vector12 = Eigen::Matrix<double, 12, 1>;
using Matrix12 = Eigen::Matrix<double, 12, 12>;
using Tangent = Eigen::Matrix<double, 12, 2>;

constexpr int kContactsPerEnvironment = 300;
constexpr double kEps[3] = {1e-5, 2e-6, 5e-5};  // eps_v h: 1e-3 x 0.01 s, and two others

struct Batch {
  FrictionContacts contacts;
  std::vector<double> start, positions;  // 3 per collision vertex, every environment's
  std::vector<double> slide;             // per contact: |u| / eps as made
};

Eigen::Vector3d random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  return Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
}

// A contact frozen at the lag: a tangent basis across a random normal, the relative-velocity
// map of a point over a triangle (barycentric weights) or of two edges (their parameters), and
// mu lambda between 0.1 and 50 N. Its vertices start anywhere and move by the same random
// motion, plus the first vertex's slide across the normal by `slide` x eps and a push along it.
Batch make_batch(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Batch batch;
  for (int e = 0; e < 3; ++e) {
    batch.contacts.begin_environment(4 * kContactsPerEnvironment, kEps[e]);
    for (int k = 0; k < kContactsPerEnvironment; ++k) {
      const Eigen::Vector3d n = random_unit(rng);
      Eigen::Matrix<double, 3, 2> basis;
      basis.col(0) = n.unitOrthogonal();
      basis.col(1) = n.cross(basis.col(0));
      const bool edge_edge = k % 2 == 1;
      const double a = 0.1 + 0.8 * unit(rng), b = 0.1 + 0.8 * unit(rng);
      const Eigen::Matrix<double, 3, 12> gamma =
          edge_edge ? kernels::edge_edge_relative_velocity_jacobian(Eigen::Vector2d(a, b))
                    : kernels::point_triangle_relative_velocity_jacobian(
                          Eigen::Vector2d(0.5 * a, 0.5 * b));
      const Tangent tangent = kernels::tangent_operator<4>(gamma, basis);
      // Slides from 0.1 to 10 eps, log-uniform: half static, half sliding.
      const double slide = std::pow(10.0, -1.0 + 2.0 * unit(rng));
      const Eigen::Vector3d shared = 1e-4 * random_unit(rng);
      const Eigen::Vector3d across =
          slide * kEps[e] * (std::cos(7.0 * k) * basis.col(0) + std::sin(7.0 * k) * basis.col(1));
      for (int c = 0; c < 4; ++c) {
        const Eigen::Vector3d x0 = 0.01 * random_unit(rng);
        const Eigen::Vector3d own =
            c == 0 ? Eigen::Vector3d(across + 1e-6 * n) : Eigen::Vector3d::Zero();
        const Eigen::Vector3d x = x0 + shared + own;
        batch.start.insert(batch.start.end(), {x0.x(), x0.y(), x0.z()});
        batch.positions.insert(batch.positions.end(), {x.x(), x.y(), x.z()});
      }
      const int vertex[4] = {4 * k, 4 * k + 1, 4 * k + 2, 4 * k + 3};
      batch.contacts.add(vertex, tangent, 0.1 + 50.0 * unit(rng));
      batch.slide.push_back(slide);
    }
  }
  return batch;
}

struct Values {
  std::vector<double> energy, gradient, hessian;
};

template <class Launcher>
Values run_stage(const Batch& b, const std::vector<double>& positions, Launcher&& launch) {
  const int n = b.contacts.buffers().count;
  Values v{std::vector<double>(n), std::vector<double>(12 * std::size_t(n)),
           std::vector<double>(144 * std::size_t(n))};
  launch(n, FrictionStage{b.contacts.buffers(), positions.data(), b.start.data(), v.energy.data(),
                          v.gradient.data(), v.hessian.data()});
  return v;
}

// Contact k's stacked displacement over the step.
Vector12 displacement(const Batch& b, const std::vector<double>& positions, int k) {
  Vector12 dx;
  for (int c = 0; c < 4; ++c) {
    const int v = b.contacts.vertex()[4 * k + c];
    for (int d = 0; d < 3; ++d) dx[3 * c + d] = positions[3 * v + d] - b.start[3 * v + d];
  }
  return dx;
}

Tangent tangent_of(const Batch& b, int k) {
  return Eigen::Map<const Tangent>(&b.contacts.tangent()[24 * std::size_t(k)]);
}

TEST(ParallelFriction, MatchesTheCpuEnginesFrictionValues) {
  const Batch b = make_batch(1);
  const Values v = run_stage(b, b.positions, parallel::SerialLauncher{});
  int sliding = 0;
  for (int k = 0; k < b.contacts.buffers().count; ++k) {
    const Vector12 dx = displacement(b, b.positions, k);
    const Tangent t = tangent_of(b, k);
    const double mu_lambda = b.contacts.mu_lambda()[k];
    const double eps = kEps[b.contacts.environment()[k]];
    ASSERT_EQ(v.energy[k], kernels::friction_potential<4>(dx, t, mu_lambda, eps)) << k;
    ASSERT_TRUE(Eigen::Map<const Vector12>(&v.gradient[12 * k]) ==
                kernels::friction_potential_gradient<4>(dx, t, mu_lambda, eps))
        << k;
    ASSERT_TRUE(Eigen::Map<const Matrix12>(&v.hessian[144 * k]) ==
                kernels::friction_potential_hessian<4>(dx, t, mu_lambda, eps))
        << k;
    sliding += b.slide[k] > 1.0;
  }
  // The batch covers both regimes.
  EXPECT_GT(sliding, 300);
  EXPECT_LT(sliding, 600);
}

TEST(ParallelFriction, GradientIsTheEnergysAndTheHessianIsPositiveSemiDefinite) {
  const Batch b = make_batch(2);
  const Values v = run_stage(b, b.positions, parallel::SerialLauncher{});
  double worst_gradient = 0.0, worst_eigenvalue = 0.0;
  for (int k = 0; k < b.contacts.buffers().count; k += 7) {
    const double eps = kEps[b.contacts.environment()[k]];
    // Central differences: their error, h^2 f0''' ~ (h / eps)^2 in the static regime, is 1e-8.
    const double h = 1e-4 * eps;
    if (std::abs(b.slide[k] - 1.0) < 1e-2) continue;  // near |u| = eps, where f0'' jumps
    const Eigen::Map<const Vector12> g(&v.gradient[12 * k]);
    Vector12 difference;
    for (int i = 0; i < 12; ++i) {
      std::vector<double> plus = b.positions, minus = b.positions;
      const int at = 3 * b.contacts.vertex()[4 * k + i / 3] + i % 3;
      plus[at] += h;
      minus[at] -= h;
      const double ep = run_stage(b, plus, parallel::SerialLauncher{}).energy[k];
      const double em = run_stage(b, minus, parallel::SerialLauncher{}).energy[k];
      difference[i] = (ep - em) / (2.0 * h);
    }
    worst_gradient = std::max(worst_gradient, (difference - g).norm() / g.norm());
    const Eigen::Map<const Matrix12> hessian(&v.hessian[144 * k]);
    const double smallest = Eigen::SelfAdjointEigenSolver<Matrix12>(hessian).eigenvalues()[0];
    worst_eigenvalue = std::min(worst_eigenvalue, smallest / hessian.norm());
  }
  EXPECT_LT(worst_gradient, 1e-6);
  EXPECT_GT(worst_eigenvalue, -1e-12);
  std::cout << "largest gradient difference " << worst_gradient
            << ", smallest Hessian eigenvalue / norm " << worst_eigenvalue << "\n";
}

TEST(ParallelFriction, ASlidingPointIsPushedBackByMuLambda) {
  const Batch b = make_batch(3);
  const Values v = run_stage(b, b.positions, parallel::SerialLauncher{});
  int checked = 0;
  for (int k = 0; k < b.contacts.buffers().count; k += 2) {  // point-triangle contacts
    if (b.slide[k] <= 1.0) continue;
    // The point's force: minus the first three gradient entries, across the normal only.
    const Eigen::Vector3d force = -Eigen::Map<const Eigen::Vector3d>(&v.gradient[12 * k]);
    const Eigen::Vector3d slide =
        displacement(b, b.positions, k).head<3>() - displacement(b, b.positions, k).segment<3>(3);
    EXPECT_NEAR(force.norm(), b.contacts.mu_lambda()[k], 1e-12 * b.contacts.mu_lambda()[k]);
    EXPECT_LT(force.dot(slide), 0.0);
    ++checked;
  }
  EXPECT_GT(checked, 100);
}

TEST(ParallelFriction, TbbAndSerialLaunchersAgreeBitForBitAndContactsAreNumberedPerEnvironment) {
  const Batch b = make_batch(4);
  const Values serial = run_stage(b, b.positions, parallel::SerialLauncher{});
  const Values threaded = run_stage(b, b.positions, parallel::TbbLauncher(2));
  EXPECT_EQ(serial.energy, threaded.energy);
  EXPECT_EQ(serial.gradient, threaded.gradient);
  EXPECT_EQ(serial.hessian, threaded.hessian);
  EXPECT_EQ(b.contacts.vertex_begin()[2], 8 * kContactsPerEnvironment);
  EXPECT_EQ(b.contacts.contact_begin()[3], 3 * kContactsPerEnvironment);
  EXPECT_EQ(b.contacts.vertex()[4 * kContactsPerEnvironment], 4 * kContactsPerEnvironment);
  EXPECT_EQ(b.contacts.environment().back(), 2);
}

}  // namespace
}  // namespace grip::solver
