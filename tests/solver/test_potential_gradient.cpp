// The incremental potential's gradient alone (IncrementalPotential::gradient), which a Newton
// iteration expected to converge evaluates instead of the full derivatives: it must be the
// derivatives' gradient bit for bit, or that iteration's convergence test would decide
// differently from the full one and the trajectory would change.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "solver/contact/candidates.hpp"
#include "solver/newton/step_targets.hpp"
#include "solver/potential/friction_lag.hpp"
#include "solver/potential/incremental_potential.hpp"
#include "tests/solver/scene_builders.hpp"

namespace grip::solver {
namespace {

using testing::rigid_box;
using testing::run_checked;
using testing::soft_box;

// A damped soft slab on a kinematic floor with friction, an affine box resting on it: every
// term has something to add (inertia, FEM elasticity and damping, the affine body's
// orthogonality, barrier and friction between all three).
SceneDescription stacked_scene() {
  SceneDescription scene;
  scene.sim.dt = 0.01;
  BodyDescription floor =
      rigid_box("floor", BodyType::kKinematic, {0.3, 0.3, 0.02}, {0, 0, -0.01 - 1.2e-3});
  floor.material.friction = 0.8;
  BodyDescription slab = soft_box("slab", {0.06, 0.06, 0.02}, 0.01, {0, 0, 0.01}, 2e5);
  slab.material.damping = 0.01;
  slab.material.friction = 0.8;
  BodyDescription box =
      rigid_box("box", BodyType::kAffine, {0.03, 0.03, 0.03}, {0.005, 0, 0.02 + 0.015 + 1.2e-3});
  box.material.friction = 0.8;
  scene.bodies = {floor, slab, box};
  return scene;
}

TEST(PotentialGradient, TheGradientAloneIsTheDerivativesGradientBitForBit) {
  Environment env(Model::build(stacked_scene()));
  run_checked(env, 15);  // the slab and the box settle into contact
  const Model& model = env.model();
  const State& state = env.state();
  const double h = model.sim().dt;

  IncrementalPotential potential(model);
  const Vertices start = env.collision_positions();
  Eigen::VectorXd q_tilde = state.q + h * state.v;
  potential.begin_step(state.q, q_tilde, state.q, start, state.kappa, h);
  const std::vector<ContactCandidate> candidates =
      find_contact_candidates(model.collision(), start, start, model.sim().d_hat);
  std::vector<FrictionContact> friction =
      lag_friction(potential.barrier(), start, candidates, false);
  ASSERT_FALSE(friction.empty());
  potential.set_friction(std::move(friction));

  // Away from the step's start (where the damping's K stands in for the elastic Hessian and
  // friction's displacement is zero): the slab's and box's DOFs moved by up to 50 um.
  std::mt19937 random(7);
  std::uniform_real_distribution<double> jitter(-5e-5, 5e-5);
  Eigen::VectorXd moved_q = state.q;
  for (const BodyModel& body : model.bodies()) {
    if (!body.has_dofs()) continue;
    // A body that keeps its shape (an affine one) moves only in its translation (its first 3
    // DOFs), so that its deformation stays at the identity's.
    const int dofs = body.deforms() ? body.dof_count : 3;
    for (int i = 0; i < dofs; ++i) moved_q[body.dof_offset + i] += jitter(random);
  }
  for (const Eigen::VectorXd& at : {state.q, moved_q}) {
    const Vertices x = collision_positions(model, at, targets_at_rest(model, state), 1.0);
    const std::vector<ContactCandidate> near =
        find_contact_candidates(model.collision(), x, x, model.sim().d_hat);
    Eigen::VectorXd full, alone;
    std::vector<Eigen::Triplet<double>> hessian;
    potential.derivatives(at, x, near, full, hessian);
    potential.gradient(at, x, near, alone);
    ASSERT_FALSE(hessian.empty());
    ASSERT_GT(full.lpNorm<Eigen::Infinity>(), 0.0);
    ASSERT_EQ(full.size(), alone.size());
    for (Eigen::Index i = 0; i < full.size(); ++i) {
      // Bit for bit: == on doubles, not a tolerance.
      ASSERT_EQ(full[i], alone[i]) << "dof " << i;
    }
  }
}

}  // namespace
}  // namespace grip::solver
