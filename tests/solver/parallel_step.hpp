#pragma once
// Environments of the data-parallel engine's potential and derivative tests, begun by the CPU
// engine and copied into the data-parallel engine's batches: scenes where every term of the
// incremental potential acts (damped soft boxes, an affine box and a driven cube resting
// within d_hat of a floor, a soft box on the affine box), each environment with its own
// velocities, step, d_hat and kappa, its barrier over the pairs near its start and its
// friction lagged there.
#include <Eigen/Core>
#include <memory>
#include <random>
#include <vector>

#include "solver/batch/model_batch.hpp"
#include "solver/environment.hpp"
#include "solver/newton/newton_solver.hpp"
#include "solver/parallel/launch.hpp"
#include "solver/parallel/newton_system.hpp"
#include "solver/parallel/potential_arrays.hpp"
#include "solver/parallel/step_start_stages.hpp"
#include "tests/solver/scene_builders.hpp"

namespace grip::solver::testing {

// Bodies `gap` (m) above a static floor, or above the affine box: every pair between them is
// within d_hat when gap < d_hat.
inline SceneDescription resting_scene(double gap, double d_hat, double dt) {
  SceneDescription scene;
  scene.sim.d_hat = d_hat;
  scene.sim.dt = dt;
  scene.sim.gravity = Eigen::Vector3d(0, 0, -9.81);
  BodyDescription floor = rigid_box("floor", BodyType::kKinematic, {0.4, 0.3, 0.02}, {0, 0, -0.01});
  BodyDescription soft = soft_box("soft", {0.03, 0.02, 0.02}, 0.01, {0.1, 0, 0.01 + gap}, 2e5);
  soft.material.damping = 5e-3;
  BodyDescription box =
      rigid_box("box", BodyType::kAffine, {0.04, 0.03, 0.02}, {0.0, 0.0, 0.01 + gap});
  box.material.density = 800.0;
  BodyDescription on_box =
      soft_box("soft on box", {0.02, 0.02, 0.01}, 0.01, {0.0, 0.0, 0.025 + 2 * gap}, 1e6);
  on_box.material.damping = 2e-3;
  BodyDescription link = driven_cube("link", {-0.1, 0, 0.01 + gap}, 2e4);
  link.script.keyframes[1].pose.position.z() += 0.005;  // its drive pulls it up off the floor
  scene.bodies = {floor, soft, box, on_box, link};
  return scene;
}

// The resting scene with the floor rising `rise` times `gap` per step (and sliding at 2 cm/s) and
// the soft box on the affine box (body 3) pinned at its top to a mount (body 5) moving 1 cm/s
// sideways: prescribed motion of scripted vertices and pinned DOFs.
inline SceneDescription moving_scene(double gap, double d_hat, double dt, double rise = 0.2) {
  SceneDescription scene = resting_scene(gap, d_hat, dt);
  scene.bodies[0].script.velocity = Eigen::Vector3d(0.02, 0, rise * gap / dt);
  BodyDescription mount =
      rigid_box("mount", BodyType::kKinematic, {0.02, 0.02, 0.004}, {0.0, 0.0, 0.032 + 2 * gap});
  mount.script.velocity = Eigen::Vector3d(0.01, 0, 0);
  Pin pin{5, {}};
  const BodyDescription& on_box = scene.bodies[3];
  for (Eigen::Index v = 0; v < on_box.vertices.rows(); ++v) {
    if (on_box.vertices(v, 2) > 0.005 - 1e-9) pin.vertices.push_back(static_cast<int>(v));
  }
  scene.bodies[3].pins.push_back(pin);
  scene.bodies.push_back(mount);
  return scene;
}

// One environment as the CPU engine begins its step: random velocities, the step's targets,
// the pairs near its start, the friction lagged there, the driven bodies' targets.
struct CpuStep {
  std::shared_ptr<const Model> model;
  State state;
  std::unique_ptr<NewtonSolver> solver;
  NewtonStep step;
  Vertices start;
  Eigen::VectorXd q_drive;
};

inline CpuStep begin_cpu_step(std::shared_ptr<const Model> model, unsigned seed) {
  const Environment env(model);
  CpuStep c{model, env.state(), std::make_unique<NewtonSolver>(*model), {}, {}, {}};
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (Eigen::Index d = 0; d < c.state.v.size(); ++d) c.state.v[d] = 0.01 * unit(random);
  c.step.h = model->sim().dt;
  c.step.targets = step_targets(*model, c.state, c.step.h);
  c.start = collision_positions(*model, c.state.q, c.step.targets, 0.0);
  c.solver->begin_step(c.state, c.start, c.step, false);
  c.q_drive = c.state.q;
  for (std::size_t b = 0; b < model->bodies().size(); ++b) {
    const BodyModel& body = model->bodies()[b];
    body.kind->set_drive_target(body.local, c.step.targets.pose_target[b], c.q_drive);
  }
  return c;
}

template <class Vector>
inline void append(std::vector<double>& to, const Vector& v) {
  to.insert(to.end(), v.data(), v.data() + v.size());
}

// The same environments in the data-parallel engine's batches: pairs and friction contacts
// copied from the CPU engine's step, the inertia targets, the damping's stiffness and the start
// positions computed by the stages (step_start_constants).
struct ParallelStep {
  parallel::FemBatch fem;
  parallel::AffineBatch affine;
  parallel::CollisionBatch collision;
  parallel::ContactPairs pairs;
  parallel::FrictionContacts friction;
  parallel::StepConstants step;
  std::vector<double> gravity, v;

  parallel::PotentialArrays<parallel::HostArray> arrays() const {
    return {fem, affine, collision, pairs, friction, step};
  }
};

inline void add_contacts(const CpuStep& c, ParallelStep& s) {
  const Model& model = *c.model;
  const int vertices = static_cast<int>(c.start.rows());
  s.pairs.begin_environment(vertices, model.sim().d_hat, c.state.kappa);
  for (const ContactCandidate& k : *c.step.near) {
    if (!k.near_at_rest) s.pairs.add(k.edge_edge, k.vertex.data(), k.mollifier_eps);
  }
  s.friction.begin_environment(vertices, model.sim().eps_v * c.step.h);
  for (const FrictionContact& f : c.solver->potential().friction().contacts()) {
    s.friction.add(f.vertex.data(), f.tangent_operator, f.mu_lambda);
  }
}

inline ParallelStep parallel_step(const std::vector<const CpuStep*>& steps) {
  std::vector<const Model*> models;
  for (const CpuStep* c : steps) models.push_back(c->model.get());
  ParallelStep s;
  s.fem = parallel::fem_batch(models);
  s.affine = parallel::affine_batch(models);
  s.collision = parallel::collision_batch(models);
  for (const CpuStep* c : steps) {
    add_contacts(*c, s);
    parallel::StepConstants& k = s.step;
    k.h.push_back(c->step.h);
    append(k.q_start, c->state.q);
    append(k.drive_target, c->q_drive);
    append(k.scripted_start, c->step.targets.kinematic_start);
    append(k.scripted_target, c->step.targets.kinematic_target);
    append(s.gravity, c->state.gravity);
    append(s.v, c->state.v);
  }
  s.step.progress.assign(steps.size(), 1.0);  // the tests' scripted bodies stand still
  parallel::fill_step_start_constants(s.step, s.fem, s.affine, s.collision, s.v, s.gravity);
  return s;
}

// The environments' Newton system at q (the batch's DOFs), contacts projected.
template <class Launcher>
parallel::NewtonSystem newton_system(const ParallelStep& s, const std::vector<double>& q,
                                     Launcher&& launch) {
  return parallel::newton_system(launch, s.fem, s.affine, s.collision, s.pairs, s.friction, s.step,
                                 q);
}

// The CPU steps of the test: two scenes, each environment its own velocities.
inline std::vector<CpuStep> cpu_steps() {
  const auto near = Model::build(resting_scene(4e-4, 1e-3, 0.01));
  const auto wide = Model::build(resting_scene(1.2e-3, 2e-3, 0.005));
  std::vector<CpuStep> steps;
  steps.push_back(begin_cpu_step(near, 1));
  steps.push_back(begin_cpu_step(wide, 2));
  steps.push_back(begin_cpu_step(near, 3));
  return steps;
}

inline std::vector<const CpuStep*> pointers(const std::vector<CpuStep>& steps) {
  std::vector<const CpuStep*> out;
  for (const CpuStep& c : steps) out.push_back(&c);
  return out;
}

// Each environment's DOFs moved by up to `reach` (m) per DOF from the step's start.
inline std::vector<Eigen::VectorXd> moved(const std::vector<CpuStep>& steps, double reach,
                                          unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<Eigen::VectorXd> q;
  for (const CpuStep& c : steps) {
    q.push_back(c.state.q);
    for (Eigen::Index d = 0; d < q.back().size(); ++d) q.back()[d] += reach * unit(random);
  }
  return q;
}

}  // namespace grip::solver::testing
