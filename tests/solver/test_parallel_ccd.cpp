// The data-parallel engine's step bound (solver/parallel/ccd_stages.hpp) on the host launchers,
// against the CPU engine's collision_free_fraction: environments whose soft, affine and driven
// bodies are pushed down through a rising scripted floor by steps of different lengths (and one
// that moves away), the broad phase's candidates of each path in one batch. Each environment's
// fraction must equal the CPU engine's bit for bit (ACCD is the same kernel, a minimum is
// exact), the serial and TBB launchers agree, and an environment's bound does not depend on
// its batch.
#include <gtest/gtest.h>

#include <vector>

#include "solver/batch/tbb_launcher.hpp"
#include "solver/contact/candidates.hpp"
#include "solver/environment.hpp"
#include "solver/newton/line_search.hpp"
#include "solver/newton/step_targets.hpp"
#include "solver/parallel/ccd_stages.hpp"
#include "solver/parallel/contact_stages.hpp"
#include "solver/parallel/launch.hpp"
#include "tests/solver/scene_builders.hpp"

namespace grip::solver {
namespace {

constexpr double kRescaling = 0.1;

struct Path {
  std::shared_ptr<const Model> model;
  Vertices start, end;
  std::vector<ContactCandidate> candidates;
};

// The scene's bodies with DOFs moved by `drop` along z (down: negative) over a step, the floor
// rising its step's way.
Path path(double drop) {
  Path p;
  p.model = Model::build(testing::every_kind_of_body());
  const Environment env(p.model);
  const StepTargets targets = step_targets(*p.model, env.state(), 0.01);
  Eigen::VectorXd q_end = env.dofs();
  for (const BodyModel& body : p.model->bodies()) {
    if (!body.has_dofs()) continue;
    const int stride = body.deforms() ? 3 : 12;  // z of each FEM vertex, or p_z of an affine body
    for (int d = 2; d < (body.deforms() ? body.dof_count : 3); d += stride) {
      q_end[body.dof_offset + d] += drop;
    }
  }
  p.start = collision_positions(*p.model, env.dofs(), targets, 0.0);
  p.end = collision_positions(*p.model, q_end, targets, 1.0);
  p.candidates =
      find_contact_candidates(p.model->collision(), p.start, p.end, p.model->sim().d_hat);
  return p;
}

struct Batch {
  parallel::ContactPairs pairs;
  std::vector<double> start, end;
};

Batch make_batch(const std::vector<Path>& paths) {
  Batch b;
  for (const Path& p : paths) {
    b.pairs.begin_environment(static_cast<int>(p.start.rows()), p.model->sim().d_hat, 1.0);
    for (const ContactCandidate& c : p.candidates) {
      b.pairs.add(c.edge_edge, c.vertex.data(), c.mollifier_eps);
    }
    b.start.insert(b.start.end(), p.start.data(), p.start.data() + p.start.size());
    b.end.insert(b.end.end(), p.end.data(), p.end.data() + p.end.size());
  }
  return b;
}

template <class Launcher>
std::vector<double> step_bounds(const Batch& b, Launcher&& launch) {
  const parallel::PairBuffers pairs = b.pairs.pairs();
  std::vector<double> toi(static_cast<std::size_t>(pairs.count));
  std::vector<double> bound(static_cast<std::size_t>(b.pairs.environment_count()));
  launch(pairs.count, parallel::CcdStage{pairs.vertex, pairs.edge_edge, b.start.data(),
                                         b.end.data(), kRescaling, toi.data()});
  launch(b.pairs.environment_count(),
         parallel::EnvironmentMinStage{b.pairs.pair_begin().data(), toi.data(), bound.data()});
  return bound;
}

const std::vector<double> kDrops{-0.2, -0.06, 0.05, -0.12};

TEST(ParallelCcd, StepBoundsEqualTheCpuEngines) {
  std::vector<Path> paths;
  for (const double drop : kDrops) paths.push_back(path(drop));
  const std::vector<double> bound = step_bounds(make_batch(paths), parallel::SerialLauncher{});
  int stopped = 0;
  for (std::size_t e = 0; e < paths.size(); ++e) {
    SCOPED_TRACE("drop " + std::to_string(kDrops[e]));
    const Path& p = paths[e];
    EXPECT_GT(p.candidates.size(), 0u);
    EXPECT_EQ(bound[e], collision_free_fraction(p.candidates, p.start, p.end, kRescaling));
    stopped += bound[e] < 1.0;
  }
  // The drops through the floor were cut short, the rise away from it was not.
  EXPECT_EQ(stopped, 3);
  EXPECT_EQ(bound[2], 1.0);
}

TEST(ParallelCcd, TbbAndSerialLaunchersAgree) {
  std::vector<Path> paths;
  for (const double drop : kDrops) paths.push_back(path(drop));
  const Batch b = make_batch(paths);
  EXPECT_EQ(step_bounds(b, parallel::SerialLauncher{}), step_bounds(b, parallel::TbbLauncher(2)));
}

TEST(ParallelCcd, AnEnvironmentsBoundDoesNotDependOnItsBatch) {
  const std::vector<double> batch =
      step_bounds(make_batch({path(-0.06), path(-0.2), path(0.05)}), parallel::SerialLauncher{});
  const std::vector<double> alone =
      step_bounds(make_batch({path(-0.2)}), parallel::SerialLauncher{});
  EXPECT_EQ(batch[1], alone[0]);
}

}  // namespace
}  // namespace grip::solver
