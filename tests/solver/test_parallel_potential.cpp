// The data-parallel engine's incremental potential (solver/parallel/potential_stages.hpp) and
// its line search's sufficient decrease (line_search_stages.hpp) on the host launchers, against
// the CPU engine's IncrementalPotential::energy and armijo, on the environments of
// tests/solver/parallel_step.hpp, where every term acts.
#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <vector>

#include "solver/batch/model_batch.hpp"
#include "solver/batch/tbb_launcher.hpp"
#include "solver/environment.hpp"
#include "solver/newton/line_search.hpp"
#include "solver/newton/newton_solver.hpp"
#include "solver/parallel/launch.hpp"
#include "solver/parallel/line_search_stages.hpp"
#include "solver/parallel/potential_arrays.hpp"
#include "solver/parallel/potential_stages.hpp"
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

double cpu_energy(const CpuStep& c, const Eigen::VectorXd& q) {
  const Vertices x = collision_positions(*c.model, q, c.step.targets, 1.0);
  return c.solver->potential().energy(q, x, *c.step.near);
}

template <class Launcher>
std::vector<double> parallel_energy(const ParallelStep& s, const std::vector<Eigen::VectorXd>& q,
                                    Launcher&& launch) {
  std::vector<double> flat;
  for (const Eigen::VectorXd& qe : q) append(flat, qe);
  const auto arrays = s.arrays();
  const parallel::PotentialBuffers b = arrays.buffers();
  parallel::PotentialStorage<parallel::HostArray> storage(b);
  std::vector<double> energy(b.environment_count);
  parallel::incremental_potential(launch, b, flat.data(), storage.work(), energy.data());
  return energy;
}

TEST(ParallelPotential, EveryTermActsInTheTestsScenes) {
  const std::vector<CpuStep> steps = cpu_steps();
  const ParallelStep s = parallel_step(pointers(steps));
  for (int e = 0; e < 3; ++e) {
    EXPECT_GT(s.pairs.pair_begin()[e + 1] - s.pairs.pair_begin()[e], 40) << e;
    EXPECT_GT(s.friction.contact_begin()[e + 1] - s.friction.contact_begin()[e], 20) << e;
  }
  // Damped and undamped tets alike: the damping's stiffness is there and it is not zero.
  EXPECT_GT(*std::max_element(s.fem.damping().begin(), s.fem.damping().end()), 0.0);
  const std::vector<double>& stiffness = s.step.damping_stiffness;
  EXPECT_GT(*std::max_element(stiffness.begin(), stiffness.end()), 0.0);
}

// step_start_constants against the CPU engine's begin_step: the start positions bit for bit,
// the inertia target q + h v + h^2 M^-1 f_gravity within round-off of the body kinds'.
TEST(ParallelPotential, StepStartConstantsAreTheCpuEnginesBeginStep) {
  const std::vector<CpuStep> steps = cpu_steps();
  const ParallelStep s = parallel_step(pointers(steps));
  const std::vector<int>& dof_begin = s.collision.dof_begin();
  const std::vector<int>& vertex_begin = s.collision.vertex_begin();
  for (std::size_t e = 0; e < steps.size(); ++e) {
    const CpuStep& c = steps[e];
    for (Eigen::Index v = 0; v < c.start.rows(); ++v) {
      for (int k = 0; k < 3; ++k) {
        ASSERT_EQ(s.step.start_positions[3 * (vertex_begin[e] + v) + k], c.start(v, k)) << e;
      }
    }
    Eigen::VectorXd q_tilde = c.state.q + c.step.h * c.state.v;
    for (const BodyModel& body : c.model->bodies()) {
      body.kind->add_gravity(body.local, c.state.gravity, c.step.h, q_tilde);
    }
    for (Eigen::Index d = 0; d < q_tilde.size(); ++d) {
      EXPECT_NEAR(s.step.q_tilde[dof_begin[e] + d], q_tilde[d],
                  1e-15 * q_tilde.cwiseAbs().maxCoeff())
          << "environment " << e << ", DOF " << d;
    }
  }
}

TEST(ParallelPotential, EnergiesMatchTheCpuEnginesAtTheStartAndMovedPoints) {
  const std::vector<CpuStep> steps = cpu_steps();
  const ParallelStep s = parallel_step(pointers(steps));
  for (const double reach : {0.0, 5e-5, 1e-4}) {
    const std::vector<Eigen::VectorXd> q = moved(steps, reach, 11);
    const std::vector<double> serial = parallel_energy(s, q, parallel::SerialLauncher{});
    const std::vector<double> tbb = parallel_energy(s, q, parallel::TbbLauncher{});
    for (int e = 0; e < 3; ++e) {
      const double cpu = cpu_energy(steps[e], q[e]);
      EXPECT_NEAR(serial[e], cpu, 1e-12 * std::abs(cpu)) << "reach " << reach << " env " << e;
      EXPECT_EQ(serial[e], tbb[e]);
    }
  }
}

// Each term's share of the energy lies far above the agreement's tolerance, so that the
// agreement above holds every term to round-off: the barrier and friction (the CPU engine's
// terms alone), and the damping (the parallel energy without the damping's stiffness).
TEST(ParallelPotential, EachTermsShareIsFarAboveTheTolerance) {
  const std::vector<CpuStep> steps = cpu_steps();
  const std::vector<Eigen::VectorXd> q = moved(steps, 1e-4, 12);
  const std::vector<double> whole =
      parallel_energy(parallel_step(pointers(steps)), q, parallel::SerialLauncher{});
  ParallelStep undamped = parallel_step(pointers(steps));
  std::vector<double>& stiffness = undamped.step.damping_stiffness;
  stiffness.assign(stiffness.size(), 0.0);
  const std::vector<double> without_damping =
      parallel_energy(undamped, q, parallel::SerialLauncher{});
  for (int e = 0; e < 3; ++e) {
    const CpuStep& c = steps[e];
    const Vertices x = collision_positions(*c.model, q[e], c.step.targets, 1.0);
    double barrier = 0.0, friction = 0.0;
    const PotentialPoint at{q[e], x, *c.step.near};
    c.solver->potential().barrier().add_energy(at, barrier);
    c.solver->potential().friction().add_energy(at, friction);
    const double h2 = c.step.h * c.step.h, scale = 1e-6 * std::abs(whole[e]);
    EXPECT_GT(h2 * barrier, scale) << "env " << e;
    EXPECT_GT(h2 * friction, scale) << "env " << e;
    EXPECT_GT(whole[e] - without_damping[e], scale) << "env " << e;
  }
}

// The damping a DampingStage adds to tet t at the batch's DOFs q: its energy, gradient (12)
// and Hessian (144).
struct TetDamping {
  double energy = 0.0;
  std::vector<double> gradient, hessian;
};

TetDamping damping_of(const ParallelStep& s, const std::vector<double>& q, int t) {
  const auto tets = static_cast<std::size_t>(s.fem.tets().count);
  std::vector<double> energy(tets), gradient(12 * tets), hessian(144 * tets);
  const parallel::StepConstants& k = s.step;
  const parallel::DampingStage stage{
      s.fem.tets(), q.data(),      k.q_start.data(), k.damping_stiffness.data(),
      k.h.data(),   energy.data(), gradient.data(),  hessian.data()};
  stage(t);
  return {energy[t],
          {gradient.begin() + 12 * t, gradient.begin() + 12 * (t + 1)},
          {hessian.begin() + 144 * t, hessian.begin() + 144 * (t + 1)}};
}

// Beta / h K exactly as the Hessian, and a gradient that central differences of the energy
// confirm, on every damped tet of the first environment; an undamped tet gets nothing.
TEST(ParallelPotential, DampingsDerivativesAreItsEnergys) {
  const std::vector<CpuStep> steps = cpu_steps();
  const ParallelStep s = parallel_step(pointers(steps));
  std::vector<double> q;
  for (const Eigen::VectorXd& qe : moved(steps, 1e-4, 14)) append(q, qe);
  int damped = 0;
  for (int t = 0; t < s.fem.tet_begin()[1]; ++t) {
    const TetDamping d = damping_of(s, q, t);
    const double beta = s.fem.damping()[t];
    if (beta == 0.0) {
      EXPECT_EQ(d.energy, 0.0);
      continue;
    }
    ++damped;
    const double c = beta / s.step.h[0];
    EXPECT_GT(d.energy, 0.0);
    for (int k = 0; k < 144; ++k)
      EXPECT_EQ(d.hessian[k], c * s.step.damping_stiffness[144 * t + k]);
    for (int k = 0; k < 12; ++k) {
      const int dof = s.fem.tet_dofs()[4 * t + k / 3] + k % 3;
      const double step = 1e-7;
      std::vector<double> plus = q, minus = q;
      plus[dof] += step;
      minus[dof] -= step;
      const double slope =
          (damping_of(s, plus, t).energy - damping_of(s, minus, t).energy) / (2.0 * step);
      EXPECT_NEAR(d.gradient[k], slope, 1e-6 * std::abs(d.gradient[k]) + 1e-12);
    }
  }
  EXPECT_GT(damped, 10);
}

struct Decrease {
  std::vector<double> alpha, energy, slope;
  std::vector<int> halvings, status;
};

// The sufficient decrease of each environment's step p[e] from q[e], its first fraction alpha.
template <class Launcher>
Decrease search(const ParallelStep& s, const std::vector<Eigen::VectorXd>& q,
                const std::vector<Eigen::VectorXd>& p, const std::vector<Eigen::VectorXd>& g,
                const std::vector<unsigned char>& held, Launcher&& launch) {
  std::vector<double> flat_q, flat_p, flat_g;
  for (std::size_t e = 0; e < q.size(); ++e) {
    append(flat_q, q[e]);
    append(flat_p, p[e]);
    append(flat_g, g[e]);
  }
  const std::size_t n = q.size();
  Decrease d;
  d.alpha.assign(n, 1.0);
  const auto arrays = s.arrays();
  const parallel::PotentialBuffers potential = arrays.buffers();
  parallel::PotentialStorage<parallel::HostArray> work(potential);
  parallel::SufficientDecreaseStorage<parallel::HostArray> storage(s.collision.dof_begin());
  const parallel::SufficientDecreaseBuffers b =
      storage.buffers(potential, work.work(), flat_q.data(), flat_p.data(), flat_g.data(),
                      held.data(), d.alpha.data());
  parallel::sufficient_decrease(launch, b);
  d.energy = storage.energy;
  d.slope = storage.slope;
  d.halvings = storage.halvings;
  d.status = storage.status;
  return d;
}

// Steps for the test's environments: down the gradient so far that Armijo halves a few times
// (a different length each), and, in the last environment, up it (no step decreases).
struct Steps {
  std::vector<Eigen::VectorXd> q, g, p;
};

Steps descent_steps(const std::vector<CpuStep>& steps, bool last_ascends) {
  Steps out;
  out.q = moved(steps, 5e-5, 13);
  const double length[3] = {3e-3, 1e-2, 3e-2};  // m, the largest DOF change of the full step
  for (std::size_t e = 0; e < steps.size(); ++e) {
    const CpuStep& c = steps[e];
    const Vertices x = collision_positions(*c.model, out.q[e], c.step.targets, 1.0);
    Eigen::VectorXd g;
    c.solver->potential().gradient(out.q[e], x, *c.step.near, g);
    for (Eigen::Index d = 0; d < g.size(); ++d) {
      if (c.model->prescribed()[d]) g[d] = 0.0;
    }
    const double sign = last_ascends && e + 1 == steps.size() ? 1.0 : -1.0;
    out.p.push_back(sign * length[e] / g.lpNorm<Eigen::Infinity>() * g);
    out.g.push_back(g);
  }
  return out;
}

TEST(ParallelLineSearch, SufficientDecreaseMatchesTheCpuEnginesArmijo) {
  const std::vector<CpuStep> steps = cpu_steps();
  const ParallelStep s = parallel_step(pointers(steps));
  const Steps st = descent_steps(steps, true);
  const std::vector<unsigned char> held(3, 0);
  const Decrease serial = search(s, st.q, st.p, st.g, held, parallel::SerialLauncher{});
  const Decrease tbb = search(s, st.q, st.p, st.g, held, parallel::TbbLauncher{});
  int halved = 0;
  for (int e = 0; e < 3; ++e) {
    const CpuStep& c = steps[e];
    double alpha = 1.0;
    int halvings = 0;
    const double energy = cpu_energy(c, st.q[e]);
    const double slope = st.g[e].dot(st.p[e]);
    const bool decreased = armijo(c.solver->potential(), *c.model, c.step.targets, *c.step.near,
                                  st.q[e], st.p[e], energy, slope, false, alpha, halvings);
    EXPECT_EQ(serial.status[e], decreased ? parallel::kSufficientDecrease : parallel::kNoDecrease);
    EXPECT_EQ(serial.alpha[e], alpha) << "env " << e;
    EXPECT_EQ(serial.halvings[e], halvings) << "env " << e;
    EXPECT_NEAR(serial.energy[e], energy, 1e-12 * std::abs(energy));
    EXPECT_NEAR(serial.slope[e], slope, 1e-12 * std::abs(slope));
    EXPECT_EQ(serial.alpha[e], tbb.alpha[e]);
    EXPECT_EQ(serial.halvings[e], tbb.halvings[e]);
    halved += halvings > 0 && decreased;
  }
  EXPECT_GE(halved, 2);  // the descending steps were cut, by different counts
  EXPECT_NE(serial.halvings[0], serial.halvings[1]);
  EXPECT_EQ(serial.status[2], parallel::kNoDecrease);  // the ascent fails, as the CPU's does
}

// A held step takes its alpha as it is; an environment's search is the same alone as beside
// others, including one that halves to the end.
TEST(ParallelLineSearch, SufficientDecreaseIsolatesEnvironments) {
  const std::vector<CpuStep> steps = cpu_steps();
  const ParallelStep s = parallel_step(pointers(steps));
  const Steps st = descent_steps(steps, true);
  const Decrease together = search(s, st.q, st.p, st.g, {0, 1, 0}, parallel::SerialLauncher{});
  EXPECT_EQ(together.status[1], parallel::kSufficientDecrease);
  EXPECT_EQ(together.alpha[1], 1.0);
  EXPECT_EQ(together.halvings[1], 0);
  for (int e = 0; e < 3; ++e) {
    const ParallelStep alone = parallel_step({&steps[e]});
    const Decrease d = search(alone, {st.q[e]}, {st.p[e]}, {st.g[e]},
                              {static_cast<unsigned char>(e == 1)}, parallel::SerialLauncher{});
    EXPECT_EQ(d.alpha[0], together.alpha[e]) << "env " << e;
    EXPECT_EQ(d.halvings[0], together.halvings[e]) << "env " << e;
    EXPECT_EQ(d.status[0], together.status[e]) << "env " << e;
    EXPECT_EQ(d.energy[0], together.energy[e]) << "env " << e;
  }
}

}  // namespace
}  // namespace grip::solver
