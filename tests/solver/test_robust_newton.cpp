// Robust Newton on the contacts that used to stall it: coplanar faces squeezed between rigid
// jaws, a thin plate landing flat, boxes stacked face to face. Every step must converge at the
// first attempt (no retry: none of these scenes is violent), with every invariant kept.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <tuple>

#include "tests/solver/scene_builders.hpp"

namespace grip::solver {
namespace {

using testing::rigid_box;
using testing::run_checked;

constexpr double kBox = 0.04;       // m, the squeezed box's edge
constexpr double kStartGap = 2e-3;  // m, each jaw's gap to the box at the start
constexpr double kFinalGap = 2e-4;  // m, the gap the jaws close to (within d_hat = 1 mm)
constexpr int kHoldSteps = 10;

struct SqueezeCase {
  double mu;
  bool gravity;
  double speed;  // m/s, of each jaw
};

std::string name(const SqueezeCase& c) {
  return "mu " + std::to_string(c.mu) + (c.gravity ? ", gravity on" : ", gravity off") + ", " +
         std::to_string(c.speed) + " m/s";
}

// A rigid 4 cm box between two rigid jaws whose faces are parallel to the box's, closing at
// `speed` from 2 mm to 0.2 mm (inside d_hat), then holding there. Body 0 is the box. Gravity,
// when on, is switched on once the jaws hold the box (as in a trial): during a slow approach
// the free box would fall out first.
SceneDescription box_between_jaws(const SqueezeCase& c) {
  SceneDescription scene;
  scene.sim.gravity = Eigen::Vector3d::Zero();
  scene.sim.dt = 0.01;
  BodyDescription box = rigid_box("box", BodyType::kAffine, {kBox, kBox, kBox}, {0, 0, 0});
  box.material.friction = c.mu;
  scene.bodies.push_back(box);
  const double close_time = (kStartGap - kFinalGap) / c.speed;
  for (const double side : {-1.0, 1.0}) {
    const double start = side * (0.5 * kBox + kStartGap + 0.005);
    const double end = side * (0.5 * kBox + kFinalGap + 0.005);
    BodyDescription jaw = rigid_box(side < 0 ? "left jaw" : "right jaw", BodyType::kKinematic,
                                    {0.01, 0.06, 0.06}, {start, 0, 0});
    jaw.material.friction = c.mu;
    jaw.script.keyframes = {{0.0, {{start, 0, 0}, Eigen::Quaterniond::Identity()}},
                            {close_time, {{end, 0, 0}, Eigen::Quaterniond::Identity()}}};
    scene.bodies.push_back(jaw);
  }
  return scene;
}

int closing_steps(const SqueezeCase& c, const SceneDescription& scene) {
  return static_cast<int>(std::ceil((kStartGap - kFinalGap) / c.speed / scene.sim.dt));
}

// Closes, then holds for kHoldSteps with gravity on or off; checks every step.
void squeeze(Environment& env, const SqueezeCase& c, const SceneDescription& scene) {
  run_checked(env, closing_steps(c, scene));
  if (c.gravity) env.set_gravity(Eigen::Vector3d(0, 0, -9.81));
  run_checked(env, kHoldSteps);
}

class RigidBoxBetweenRigidJaws : public ::testing::TestWithParam<SqueezeCase> {};

TEST_P(RigidBoxBetweenRigidJaws, EveryStepConvergesWithoutRetry) {
  const SqueezeCase c = GetParam();
  const SceneDescription scene = box_between_jaws(c);
  Environment env(Model::build(scene));
  squeeze(env, c, scene);
  EXPECT_EQ(env.statistics().retries, 0) << name(c);
  EXPECT_LE(env.statistics().max_step_iterations, 40) << name(c);
  // Both jaws press on the box at the end, unless it slid out under gravity without friction.
  if (c.mu > 0.0 || !c.gravity) {
    EXPECT_EQ(env.last_step().contact_forces.size(), 2u) << name(c);
  }
}

INSTANTIATE_TEST_SUITE_P(
    FrictionGravitySpeed, RigidBoxBetweenRigidJaws,
    ::testing::Values(SqueezeCase{0.0, false, 0.01}, SqueezeCase{0.0, false, 0.05},
                      SqueezeCase{0.0, true, 0.01}, SqueezeCase{0.0, true, 0.05},
                      SqueezeCase{0.5, false, 0.01}, SqueezeCase{0.5, false, 0.05},
                      SqueezeCase{0.5, true, 0.01}, SqueezeCase{0.5, true, 0.05}));

// The closing force, the squeeze's physics, does not depend on gravity acting across it: the
// convergence test asks the same force accuracy with gravity on and off.
TEST(RobustNewton, SqueezeForceIsTheSameWithGravityOnAndOff) {
  double force[2];
  for (const bool gravity : {false, true}) {
    const SqueezeCase c{0.5, gravity, 0.01};
    const SceneDescription scene = box_between_jaws(c);
    Environment env(Model::build(scene));
    squeeze(env, c, scene);
    double total = 0.0;
    for (const PairForce& pair : env.last_step().contact_forces) total += pair.normal_force;
    force[gravity ? 1 : 0] = total;
  }
  EXPECT_GT(force[0], 1.0);
  EXPECT_NEAR(force[1], force[0], 1e-3 * force[0]);
}

// A 10 cm x 10 cm x 2 mm plate dropped flat from 5 mm onto a rigid floor: hundreds of coplanar
// vertex-face and edge-edge pairs reach d_hat at once.
TEST(RobustNewton, ThinPlateDroppedFlatLandsAndRests) {
  SceneDescription scene;
  scene.sim.dt = 0.01;
  scene.bodies.push_back(rigid_box("floor", BodyType::kKinematic, {0.3, 0.3, 0.02}, {0, 0, -0.01}));
  scene.bodies.push_back(
      rigid_box("plate", BodyType::kAffine, {0.1, 0.1, 0.002}, {0, 0, 0.001 + 0.005}));
  Environment env(Model::build(scene));
  run_checked(env, 60);
  EXPECT_EQ(env.statistics().retries, 0);
  const Eigen::Vector3d centre = env.center_of_mass(1);
  EXPECT_GT(centre.z(), 0.001);         // above the floor
  EXPECT_LT(centre.z(), 0.001 + 1e-3);  // and resting on it, within d_hat
  EXPECT_LT(env.center_of_mass_velocity(1).norm(), 1e-3);
}

// Three boxes stacked face to face on a floor, each 0.5 mm above the one below (inside d_hat),
// at rest: the stack settles onto its barrier gaps (each within d_hat) and stays there.
TEST(RobustNewton, FaceToFaceStackStaysAtRest) {
  SceneDescription scene;
  scene.sim.dt = 0.01;
  scene.bodies.push_back(rigid_box("floor", BodyType::kKinematic, {0.3, 0.3, 0.02}, {0, 0, -0.01}));
  constexpr double kGap = 5e-4;
  for (int k = 0; k < 3; ++k) {
    scene.bodies.push_back(rigid_box("box " + std::to_string(k), BodyType::kAffine,
                                     {kBox, kBox, kBox},
                                     {0, 0, kGap + 0.5 * kBox + k * (kBox + kGap)}));
  }
  Environment env(Model::build(scene));
  run_checked(env, 50);
  EXPECT_EQ(env.statistics().retries, 0);
  const double d_hat = scene.sim.d_hat;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d centre = env.center_of_mass(k + 1);
    // No sideways drift beyond what the faces' diagonal triangulation breaks symmetry by.
    EXPECT_LT(centre.head<2>().norm(), 0.1 * d_hat) << "box " << k;
    const double lowest = 0.5 * kBox + k * kBox;  // with zero gaps
    EXPECT_GT(centre.z(), lowest) << "box " << k;
    EXPECT_LT(centre.z(), lowest + (k + 1) * d_hat) << "box " << k;
    EXPECT_LT(env.center_of_mass_velocity(k + 1).norm(), 1e-3) << "box " << k;
  }
}

}  // namespace
}  // namespace grip::solver
