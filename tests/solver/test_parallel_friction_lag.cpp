// The data-parallel friction lag (solver/parallel/friction_lag_stages.hpp) on the host
// launchers against the CPU engine's lag_friction, on the environments of
// tests/solver/parallel_step.hpp: from each environment's candidates near its step's start,
// the same contacts in the same order, their mu lambda and tangent operators bit for bit;
// with every third pair's mu set to zero, those left out, or kept at zero friction when the
// policy asks; serial and TBB launchers alike.
#include <gtest/gtest.h>

#include <vector>

#include "solver/batch/tbb_launcher.hpp"
#include "solver/parallel/friction_lag_stages.hpp"
#include "solver/parallel/launch.hpp"
#include "solver/potential/friction_lag.hpp"
#include "tests/solver/parallel_step.hpp"

namespace grip::solver {
namespace {

using testing::cpu_steps;
using testing::CpuStep;
using testing::parallel_step;
using testing::ParallelStep;
using testing::pointers;

// Each environment's candidates near its start, every third one's mu set to zero with
// `some_frictionless`.
std::vector<std::vector<ContactCandidate>> candidates(const std::vector<CpuStep>& steps,
                                                      bool some_frictionless) {
  std::vector<std::vector<ContactCandidate>> out;
  for (const CpuStep& c : steps) {
    out.push_back(*c.step.near);
    if (!some_frictionless) continue;
    for (std::size_t k = 0; k < out.back().size(); k += 3) out.back()[k].friction = 0.0;
  }
  return out;
}

struct Lagged {
  std::vector<int> vertex, environment, contact_begin;
  std::vector<double> tangent, mu_lambda;
};

template <class Launcher>
Lagged lag(const ParallelStep& s, const std::vector<std::vector<ContactCandidate>>& near,
           bool at_zero_mu, Launcher&& launch) {
  std::vector<int> vertex, environment, candidate_begin{0};
  std::vector<unsigned char> edge_edge, near_at_rest;
  std::vector<double> friction, mollifier_eps;
  for (std::size_t e = 0; e < near.size(); ++e) {
    for (const ContactCandidate& c : near[e]) {
      for (const int v : c.vertex) vertex.push_back(s.collision.vertex_begin()[e] + v);
      edge_edge.push_back(c.edge_edge ? 1 : 0);
      near_at_rest.push_back(c.near_at_rest ? 1 : 0);
      friction.push_back(c.friction);
      mollifier_eps.push_back(c.mollifier_eps);
      environment.push_back(static_cast<int>(e));
    }
    candidate_begin.push_back(static_cast<int>(environment.size()));
  }
  const int count = static_cast<int>(environment.size());
  std::vector<int> keep(count + 1);
  std::vector<double> mu_lambda(count), tangent(24 * std::size_t(count));
  const parallel::FrictionLagBuffers b{count,
                                       vertex.data(),
                                       edge_edge.data(),
                                       near_at_rest.data(),
                                       friction.data(),
                                       mollifier_eps.data(),
                                       environment.data(),
                                       candidate_begin.data(),
                                       static_cast<int>(near.size()),
                                       s.step.start_positions.data(),
                                       s.pairs.d_hat().data(),
                                       s.pairs.kappa().data(),
                                       at_zero_mu,
                                       keep.data(),
                                       mu_lambda.data(),
                                       tangent.data()};
  const int total = parallel::count_lagged_contacts(launch, b);
  Lagged out{std::vector<int>(4 * std::size_t(total)), std::vector<int>(total),
             std::vector<int>(near.size() + 1), std::vector<double>(24 * std::size_t(total)),
             std::vector<double>(total)};
  parallel::write_lagged_contacts(launch, b,
                                  {out.vertex.data(), out.tangent.data(), out.mu_lambda.data(),
                                   out.environment.data(), out.contact_begin.data()});
  return out;
}

// Each environment's contacts equal lag_friction's, in its order, bit for bit; returns how many
// there are in all.
int expect_cpu_lag(const std::vector<CpuStep>& steps, const ParallelStep& s,
                   const std::vector<std::vector<ContactCandidate>>& near, bool at_zero_mu,
                   const Lagged& got) {
  int total = 0;
  for (std::size_t e = 0; e < steps.size(); ++e) {
    const CpuStep& c = steps[e];
    const std::vector<FrictionContact> cpu =
        lag_friction(c.solver->potential().barrier(), c.start, near[e], at_zero_mu);
    const int first = got.contact_begin[e];
    EXPECT_EQ(got.contact_begin[e + 1] - first, static_cast<int>(cpu.size())) << "env " << e;
    for (std::size_t k = 0; k < cpu.size() && first + k < got.mu_lambda.size(); ++k) {
      const std::size_t at = first + k;
      for (int v = 0; v < 4; ++v) {
        EXPECT_EQ(got.vertex[4 * at + v], s.collision.vertex_begin()[e] + cpu[k].vertex[v]);
      }
      EXPECT_EQ(got.environment[at], static_cast<int>(e));
      EXPECT_EQ(got.mu_lambda[at], cpu[k].mu_lambda);
      const Eigen::Map<const Eigen::Matrix<double, 12, 2>> tangent(&got.tangent[24 * at]);
      EXPECT_EQ(tangent, cpu[k].tangent_operator) << "env " << e << " contact " << k;
    }
    total += static_cast<int>(cpu.size());
  }
  return total;
}

TEST(ParallelFrictionLag, MatchesTheCpuEnginesLag) {
  const std::vector<CpuStep> steps = cpu_steps();
  const ParallelStep s = parallel_step(pointers(steps));
  const auto near = candidates(steps, false);
  const Lagged serial = lag(s, near, false, parallel::SerialLauncher{});
  EXPECT_GT(expect_cpu_lag(steps, s, near, false, serial), 100);
  const Lagged tbb = lag(s, near, false, parallel::TbbLauncher{});
  EXPECT_EQ(serial.vertex, tbb.vertex);
  EXPECT_EQ(serial.mu_lambda, tbb.mu_lambda);
  EXPECT_EQ(serial.tangent, tbb.tangent);
}

TEST(ParallelFrictionLag, FrictionlessPairsFollowThePolicy) {
  const std::vector<CpuStep> steps = cpu_steps();
  const ParallelStep s = parallel_step(pointers(steps));
  const auto near = candidates(steps, true);
  const int left_out =
      expect_cpu_lag(steps, s, near, false, lag(s, near, false, parallel::SerialLauncher{}));
  const int kept =
      expect_cpu_lag(steps, s, near, true, lag(s, near, true, parallel::SerialLauncher{}));
  EXPECT_GT(kept, left_out);  // the frictionless pairs that push are kept, at zero
}

}  // namespace
}  // namespace grip::solver
