// The data-parallel line search's stages (solver/parallel/line_search_stages.hpp) on the host
// launchers against the CPU engine's: environments of scenes with soft boxes, each with its own
// Newton step (random, large enough that the whole step inverts tets) and first fraction;
// every environment's kept fraction and halvings equal the CPU engine's
// halve_until_no_inversion, an environment that starts inverted fails as it does, the serial and
// TBB launchers agree, and an environment's result does not depend on its batch.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "solver/batch/model_batch.hpp"
#include "solver/batch/tbb_launcher.hpp"
#include "solver/environment.hpp"
#include "solver/newton/line_search.hpp"
#include "solver/parallel/launch.hpp"
#include "solver/parallel/line_search_stages.hpp"
#include "tests/solver/parallel_batch.hpp"

namespace grip::solver {
namespace {

struct Step {
  std::vector<std::shared_ptr<const Model>> models;
  std::vector<Eigen::VectorXd> q, p;  // per environment
  std::vector<double> flat_q, flat_p, first_alpha;
};

// Environment e moved by up to 2 mm per DOF and stepped by up to `reach` (m) per DOF; with
// `inverted`, its first soft box's first tet starts inverted (a vertex pushed through).
Step make_step(const std::vector<std::shared_ptr<const Model>>& models,
               const std::vector<double>& reach, int inverted = -1) {
  Step s{models, {}, {}, {}, {}, {}};
  for (std::size_t e = 0; e < models.size(); ++e) {
    std::mt19937 random(70 + static_cast<unsigned>(e));
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const Environment env(models[e]);
    Eigen::VectorXd q = env.dofs(), p(q.size());
    for (Eigen::Index d = 0; d < q.size(); ++d) {
      q[d] += 0.002 * unit(random);
      p[d] = reach[e] * unit(random);
    }
    if (static_cast<int>(e) == inverted) {
      const BodyModel& soft = models[e]->bodies()[1];  // the soft box (every_kind_of_body)
      q.segment<3>(soft.dof_offset) =
          q.segment<3>(soft.dof_offset + 3) +
          2.0 * (q.segment<3>(soft.dof_offset + 3) - q.segment<3>(soft.dof_offset));
    }
    s.q.push_back(q);
    s.p.push_back(p);
    s.flat_q.insert(s.flat_q.end(), q.data(), q.data() + q.size());
    s.flat_p.insert(s.flat_p.end(), p.data(), p.data() + p.size());
    s.first_alpha.push_back(1.0 - 0.1 * static_cast<double>(e));  // as a CCD bound would cut it
  }
  return s;
}

struct Halved {
  std::vector<double> alpha;
  std::vector<int> halvings, status;
};

template <class Launcher>
Halved halve(const Step& s, Launcher&& launch) {
  std::vector<const Model*> raw;
  for (const auto& m : s.models) raw.push_back(m.get());
  const parallel::FemBatch fem = parallel::fem_batch(raw);
  const auto environments = s.models.size();
  Halved out{s.first_alpha, std::vector<int>(environments), std::vector<int>(environments)};
  std::vector<double> ratio(fem.rest_volume().size()), smallest(environments);
  int halving = 0;
  const parallel::StepHalvingBuffers b{fem.tets(),
                                       fem.tet_begin().data(),
                                       static_cast<int>(environments),
                                       s.flat_q.data(),
                                       s.flat_p.data(),
                                       out.alpha.data(),
                                       out.halvings.data(),
                                       out.status.data(),
                                       ratio.data(),
                                       smallest.data(),
                                       &halving};
  parallel::halve_until_no_inversion(launch, b);
  return out;
}

TEST(ParallelLineSearch, HalvesEachEnvironmentAsTheCpuEngineDoes) {
  const Step s = make_step({testing::mixed_scene(), testing::soft_scene(), testing::mixed_scene(),
                            testing::soft_scene()},
                           {0.001, 0.05, 0.2, 0.02}, 3);
  parallel::SerialLauncher launch;
  const Halved parallel = halve(s, launch);
  int halved = 0;
  for (int e = 0; e < 4; ++e) {
    SCOPED_TRACE("environment " + std::to_string(e));
    double alpha = s.first_alpha[e];
    int halvings = 0;
    const bool kept = halve_until_no_inversion(*s.models[e], s.q[e], s.p[e], alpha, halvings);
    EXPECT_EQ(parallel.status[e], kept ? parallel::kNoInversion : parallel::kStepTooSmall);
    EXPECT_EQ(parallel.alpha[e], alpha);
    EXPECT_EQ(parallel.halvings[e], halvings);
    halved += halvings > 0 && kept ? 1 : 0;
  }
  EXPECT_EQ(parallel.halvings[0], 0);                      // a small step inverts nothing
  EXPECT_GE(halved, 2);                                    // the large ones are cut
  EXPECT_EQ(parallel.status[3], parallel::kStepTooSmall);  // it starts inverted
}

TEST(ParallelLineSearch, LaunchersAgreeAndAnEnvironmentDoesNotDependOnItsBatch) {
  const Step four = make_step({testing::mixed_scene(), testing::soft_scene(),
                               testing::mixed_scene(), testing::soft_scene()},
                              {0.001, 0.05, 0.2, 0.02}, 3);
  parallel::SerialLauncher serial;
  parallel::TbbLauncher threads(2);
  const Halved one = halve(four, serial), two = halve(four, threads);
  EXPECT_EQ(one.alpha, two.alpha);
  EXPECT_EQ(one.halvings, two.halvings);
  // Alone, the first environment halves a few times; beside one that halves to the end, the same.
  const Step alone = make_step({testing::mixed_scene()}, {0.2});
  const Step first_of_two =
      make_step({testing::mixed_scene(), testing::soft_scene()}, {0.2, 0.05}, 1);
  const Halved solo = halve(alone, serial), pair = halve(first_of_two, serial);
  EXPECT_GT(solo.halvings[0], 0);
  EXPECT_EQ(solo.alpha[0], pair.alpha[0]);
  EXPECT_EQ(solo.halvings[0], pair.halvings[0]);
  EXPECT_EQ(pair.status[1], parallel::kStepTooSmall);  // the other halved to the end
}

}  // namespace
}  // namespace grip::solver
