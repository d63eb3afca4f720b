// The data-parallel broad phase (solver/parallel/broad_phase.hpp) on the host launchers against
// the CPU engine's find_contact_candidates: environments of scenes that mix scripted, FEM,
// affine and driven bodies, each with its own d_hat (2 to 8 cm, so that bodies meet the floor
// and each other and the soft boxes meet themselves; one scene built with a d_hat at which its
// soft box has pairs near at rest), each on its own path (DOFs moved by up to 1 cm, the floor
// part way up). Every environment's candidates equal the CPU engine's, in its order, field for
// field; the serial and TBB launchers give the same lists; an environment's list does not
// depend on its batch; bodies of one collision group are never swept against each other. Then the
// reach filter (solver/parallel/reach_stages.hpp) against the CPU engine's within_reach: the pairs
// within reach and those CCD watches, each environment's equal to the CPU engine's, in its order.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "solver/batch/model_batch.hpp"
#include "solver/batch/tbb_launcher.hpp"
#include "solver/contact/candidates.hpp"
#include "solver/environment.hpp"
#include "solver/newton/step_targets.hpp"
#include "solver/parallel/broad_phase.hpp"
#include "solver/parallel/launch.hpp"
#include "solver/parallel/reach_stages.hpp"
#include "tests/solver/scene_builders.hpp"

namespace grip::solver {
namespace {

// The scene of every kind of body, its bodies pushed together (the soft box 1 cm above the
// floor, the affine box beside it), built with `d_hat` so that its near-at-rest lists are
// that d_hat's. The floor comes last, so that the edges of a body without DOFs (listed first
// in their pairs) are not the lower-numbered ones.
std::shared_ptr<const Model> crowded_scene(double d_hat) {
  SceneDescription scene = testing::every_kind_of_body();
  scene.bodies[1].pose.position = {0.0, 0.0, 0.02};
  scene.bodies[2].pose.position = {0.035, 0.0, 0.03};
  scene.bodies[3].pose.position = {-0.03, 0.0, 0.02};
  scene.sim.d_hat = d_hat;
  std::rotate(scene.bodies.begin(), scene.bodies.begin() + 1, scene.bodies.end());
  return Model::build(scene);
}

struct Paths {
  std::vector<std::shared_ptr<const Model>> models;
  std::vector<Vertices> start, end;                 // per environment, the CPU engine's
  std::vector<double> flat_start, flat_end, d_hat;  // the batch's
};

// Each environment's collision vertices at a random state and at another up to `motion` away
// (per DOF), the floor 0.3 and 1.0 of its way up.
Paths make_paths(const std::vector<std::shared_ptr<const Model>>& models,
                 const std::vector<double>& d_hat, double motion = 0.01) {
  Paths p{models, {}, {}, {}, {}, d_hat};
  for (std::size_t e = 0; e < models.size(); ++e) {
    const Model& model = *models[e];
    std::mt19937 random(40 + static_cast<unsigned>(e));  // whatever the batch
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const Environment env(models[e]);
    const StepTargets targets = step_targets(model, env.state(), 0.01);
    Eigen::VectorXd q = env.dofs();
    for (Eigen::Index d = 0; d < q.size(); ++d) q[d] += 0.004 * unit(random);
    p.start.push_back(collision_positions(model, q, targets, 0.3));
    for (Eigen::Index d = 0; d < q.size(); ++d) q[d] += motion * unit(random);
    p.end.push_back(collision_positions(model, q, targets, 1.0));
    p.flat_start.insert(p.flat_start.end(), p.start.back().data(),
                        p.start.back().data() + p.start.back().size());
    p.flat_end.insert(p.flat_end.end(), p.end.back().data(),
                      p.end.back().data() + p.end.back().size());
  }
  return p;
}

std::vector<const Model*> raw(const Paths& p) {
  std::vector<const Model*> models;
  for (const auto& m : p.models) models.push_back(m.get());
  return models;
}

// Environment e's candidates in the batch's arrays against the CPU engine's.
void expect_cpu_candidates(const Paths& p, const parallel::SurfaceBatch& surfaces,
                           const parallel::HostBroadPhase& found, int e) {
  const CollisionMesh& mesh = p.models[e]->collision();
  const std::vector<ContactCandidate> cpu =
      find_contact_candidates(mesh, p.start[e], p.end[e], p.d_hat[e]);
  const int begin = found.environment_begin()[e], end = found.environment_begin()[e + 1];
  ASSERT_EQ(end - begin, static_cast<int>(cpu.size()));
  const int first_vertex = surfaces.vertex_begin()[e];
  for (int k = begin; k < end; ++k) {
    const ContactCandidate& c = cpu[static_cast<std::size_t>(k - begin)];
    SCOPED_TRACE("pair " + std::to_string(k - begin));
    ASSERT_EQ(found.edge_edge()[k] != 0, c.edge_edge);
    for (int corner = 0; corner < 4; ++corner) {
      ASSERT_EQ(found.vertex()[4 * k + corner] - first_vertex, c.vertex[corner]);
    }
    EXPECT_EQ(found.friction()[k], c.friction);
    EXPECT_EQ(found.mollifier_eps()[k], c.mollifier_eps);
    EXPECT_EQ(found.near_at_rest()[k] != 0, c.near_at_rest);
    EXPECT_EQ(found.environment()[k], e);
  }
}

TEST(ParallelBroadPhase, FindsTheCpuEnginesCandidatesInItsOrder) {
  const Paths p = make_paths({crowded_scene(1e-3), crowded_scene(0.02), crowded_scene(1e-3)},
                             {0.02, 0.05, 0.08});
  const parallel::SurfaceBatch surfaces = parallel::surface_batch(raw(p));
  parallel::HostBroadPhase found(surfaces);
  parallel::SerialLauncher launch;
  found.find(launch, p.flat_start, p.flat_end, p.d_hat);
  for (int e = 0; e < 3; ++e) {
    SCOPED_TRACE("environment " + std::to_string(e));
    expect_cpu_candidates(p, surfaces, found, e);
  }
  // Every kind of pair is there: of one body and of two, near at rest and not.
  int edge_edge = 0, near_at_rest = 0, own = 0;
  const parallel::SurfaceBuffers s = surfaces.buffers();
  for (int k = 0; k < found.count(); ++k) {
    edge_edge += found.edge_edge()[k];
    near_at_rest += found.near_at_rest()[k];
    const int* v = &found.vertex()[4 * k];
    own += s.vertex_body[v[0]] == s.vertex_body[v[3]] ? 1 : 0;
  }
  EXPECT_GT(edge_edge, 0);
  EXPECT_LT(edge_edge, found.count());
  EXPECT_GT(near_at_rest, 0);
  EXPECT_GT(own, near_at_rest);
  EXPECT_LT(own, found.count());
}

TEST(ParallelBroadPhase, TbbAndSerialLaunchersAgree) {
  const Paths p = make_paths({crowded_scene(1e-3), crowded_scene(0.02)}, {0.05, 0.03});
  const parallel::SurfaceBatch surfaces = parallel::surface_batch(raw(p));
  parallel::HostBroadPhase serial(surfaces), threaded(surfaces);
  parallel::SerialLauncher one;
  parallel::TbbLauncher two(2);
  serial.find(one, p.flat_start, p.flat_end, p.d_hat);
  threaded.find(two, p.flat_start, p.flat_end, p.d_hat);
  EXPECT_GT(serial.count(), 0);
  EXPECT_EQ(serial.vertex(), threaded.vertex());
  EXPECT_EQ(serial.edge_edge(), threaded.edge_edge());
  EXPECT_EQ(serial.environment_begin(), threaded.environment_begin());
}

TEST(ParallelBroadPhase, AnEnvironmentsCandidatesDoNotDependOnItsBatch) {
  const Paths three = make_paths({crowded_scene(0.02), crowded_scene(1e-3), crowded_scene(0.02)},
                                 {0.05, 0.08, 0.05});
  const Paths alone = make_paths({crowded_scene(0.02)}, {0.05});
  const parallel::SurfaceBatch batch_surfaces = parallel::surface_batch(raw(three));
  const parallel::SurfaceBatch alone_surfaces = parallel::surface_batch(raw(alone));
  parallel::HostBroadPhase in_batch(batch_surfaces), solo(alone_surfaces);
  parallel::SerialLauncher launch;
  in_batch.find(launch, three.flat_start, three.flat_end, three.d_hat);
  solo.find(launch, alone.flat_start, alone.flat_end, alone.d_hat);
  ASSERT_EQ(solo.environment_begin()[1], in_batch.environment_begin()[1]);
  EXPECT_TRUE(std::equal(solo.vertex().begin(), solo.vertex().end(), in_batch.vertex().begin()));
  EXPECT_TRUE(
      std::equal(solo.friction().begin(), solo.friction().end(), in_batch.friction().begin()));
  EXPECT_EQ(solo.axis()[0], in_batch.axis()[0]);
}

// A gripper-like scene: a soft bar standing 10 cm tall in 5 mm cells beside a rigid bar 40 cm
// long (8 vertices). The whole extent is longest along x, but the soft bar's many small
// primitives lie along z, where they overlap least: the sweep runs along z, and the candidates
// are still the CPU engine's.
TEST(ParallelBroadPhase, SweepsAlongWhereThePrimitivesLie) {
  SceneDescription scene;
  scene.sim.d_hat = 1e-3;
  scene.bodies = {
      testing::soft_box("standing", {0.02, 0.02, 0.1}, 0.005, {0.0, 0.0, 0.05}, 1e6),
      testing::rigid_box("bar", BodyType::kKinematic, {0.4, 0.02, 0.02}, {0.0, 0.0, -0.0105})};
  const Paths p = make_paths({Model::build(scene)}, {1e-3}, 0.0);
  const parallel::SurfaceBatch surfaces = parallel::surface_batch(raw(p));
  parallel::HostBroadPhase found(surfaces);
  parallel::SerialLauncher launch;
  found.find(launch, p.flat_start, p.flat_end, p.d_hat);
  EXPECT_EQ(found.axis()[0], 2);
  EXPECT_GT(found.count(), 0);
  expect_cpu_candidates(p, surfaces, found, 0);
}

// The sweep runs per pair of bodies that may touch: the crowded scene with its soft box and its
// affine box in one collision group (as a hand's links are) still gives the CPU engine's list,
// with no pair of those two bodies and pairs of each with the others.
TEST(ParallelBroadPhase, SweepsOnlyPairsOfBodiesThatMayTouch) {
  SceneDescription scene = testing::every_kind_of_body();
  scene.bodies[1].pose.position = {0.0, 0.0, 0.02};
  scene.bodies[2].pose.position = {0.03, 0.0, 0.025};
  scene.bodies[3].pose.position = {-0.03, 0.0, 0.02};
  scene.bodies[1].collision_group = scene.bodies[2].collision_group = 1;
  const Paths p = make_paths({Model::build(scene)}, {0.05});
  const parallel::SurfaceBatch surfaces = parallel::surface_batch(raw(p));
  parallel::HostBroadPhase found(surfaces);
  parallel::SerialLauncher launch;
  found.find(launch, p.flat_start, p.flat_end, p.d_hat);
  expect_cpu_candidates(p, surfaces, found, 0);
  const parallel::SurfaceBuffers s = surfaces.buffers();
  int grouped = 0, soft_with_others = 0, box_with_others = 0;
  for (int k = 0; k < found.count(); ++k) {
    const int* v = &found.vertex()[4 * k];
    const int a = s.vertex_body[v[0]], b = s.vertex_body[v[3]];
    grouped += (a == 1 && b == 2) || (a == 2 && b == 1) ? 1 : 0;
    soft_with_others += (a == 1) != (b == 1) && a != 2 && b != 2 ? 1 : 0;
    box_with_others += (a == 2) != (b == 2) && a != 1 && b != 1 ? 1 : 0;
  }
  EXPECT_EQ(grouped, 0);
  EXPECT_GT(soft_with_others, 0);
  EXPECT_GT(box_with_others, 0);
}

// The reach filter's lists over a broad phase's candidates (each list's first entries count).
struct Reach {
  parallel::ReachStorage<parallel::HostArray> lists;
  int reachable = 0, watched = 0;
};

Reach reach(const Paths& p, const parallel::SurfaceBatch& surfaces,
            const parallel::HostBroadPhase& found, const std::vector<double>& ccd_rescaling) {
  const parallel::SurfaceBuffers s = surfaces.buffers();
  Reach out{parallel::ReachStorage<parallel::HostArray>(s, found.count())};
  parallel::SerialLauncher launch;
  parallel::find_within_reach(
      launch,
      out.lists.buffers(s, p.flat_start.data(), p.flat_end.data(), p.d_hat.data(),
                        ccd_rescaling.data(), found.count(), found.vertex().data(),
                        found.edge_edge().data(), found.environment().data(),
                        found.environment_begin().data()),
      out.reachable, out.watched);
  return out;
}

// Environment e's list (indices into the candidates) against the CPU engine's pairs.
void expect_list(const std::vector<int>& list, int begin, int end,
                 const parallel::HostBroadPhase& found, int first_vertex,
                 const std::vector<ContactCandidate>& cpu) {
  ASSERT_EQ(end - begin, static_cast<int>(cpu.size()));
  for (int k = begin; k < end; ++k) {
    const int c = list[static_cast<std::size_t>(k)];
    for (int corner = 0; corner < 4; ++corner) {
      ASSERT_EQ(found.vertex()[4 * c + corner] - first_vertex,
                cpu[static_cast<std::size_t>(k - begin)].vertex[corner]);
    }
  }
}

// Environment e's reach lists against the CPU engine's within_reach; adds the candidates it
// leaves out and the pairs CCD watches beyond reach.
void expect_cpu_reach(const Paths& p, const parallel::SurfaceBatch& surfaces,
                      const parallel::HostBroadPhase& found, const Reach& r,
                      const std::vector<double>& ccd_rescaling, int e, int& left_out,
                      int& ccd_only) {
  const CollisionMesh& mesh = p.models[e]->collision();
  const std::vector<ContactCandidate> candidates =
      find_contact_candidates(mesh, p.start[e], p.end[e], p.d_hat[e]);
  std::vector<ContactCandidate> ccd;
  const std::vector<ContactCandidate> within = within_reach(
      mesh.vertex_body, candidates, p.start[e], p.end[e], p.d_hat[e], &ccd, ccd_rescaling[e]);
  EXPECT_GT(within.size(), 0u);
  left_out += static_cast<int>(candidates.size() - within.size());
  ccd_only += static_cast<int>(ccd.size() - within.size());
  const int first_vertex = surfaces.vertex_begin()[e];
  expect_list(r.lists.reachable, r.lists.reachable_begin[e], r.lists.reachable_begin[e + 1], found,
              first_vertex, within);
  expect_list(r.lists.ccd, r.lists.ccd_begin[e], r.lists.ccd_begin[e + 1], found, first_vertex,
              ccd);
}

TEST(ParallelBroadPhase, ReachFilterKeepsWhatTheCpuEnginesKeeps) {
  const std::vector<double> ccd_rescaling{0.1, 0.5, 0.1};
  int left_out = 0, ccd_only = 0;
  for (const double motion : {5e-4, 1e-2}) {  // most pairs beyond reach; some only for CCD
    SCOPED_TRACE("motion " + std::to_string(motion));
    const Paths p = make_paths({crowded_scene(1e-3), crowded_scene(0.02), crowded_scene(1e-3)},
                               {0.002, 0.005, 0.003}, motion);
    const parallel::SurfaceBatch surfaces = parallel::surface_batch(raw(p));
    parallel::HostBroadPhase found(surfaces);
    parallel::SerialLauncher launch;
    found.find(launch, p.flat_start, p.flat_end, p.d_hat);
    const Reach r = reach(p, surfaces, found, ccd_rescaling);
    for (int e = 0; e < 3; ++e) {
      SCOPED_TRACE("environment " + std::to_string(e));
      expect_cpu_reach(p, surfaces, found, r, ccd_rescaling, e, left_out, ccd_only);
    }
  }
  EXPECT_GT(left_out, 500);  // the filter has work to do (about 810 at the smaller motion)
  EXPECT_GT(ccd_only, 0);
}

}  // namespace
}  // namespace grip::solver
