// Driven bodies (BodyDescription::drive_stiffness): an affine body pulled towards its script's
// pose by a spring inside the step. Pressed against a wall, it pushes with the spring's force,
// drive_stiffness times how far its target lies past where the wall stops it; it does not fall
// under gravity; and bodies of one collision group never touch.
#include <gtest/gtest.h>

#include "solver/environment.hpp"
#include "tests/solver/scene_builders.hpp"

namespace grip::solver {
namespace {

constexpr double kStiffness = 2e4;  // N/m

double pair_force(const Environment& env) {
  double force = 0.0;
  for (const PairForce& pair : env.last_step().contact_forces) force += pair.normal_force;
  return force;
}

// A 2 cm driven cube above a kinematic floor (top face at z = 0), its target `depth` below
// where it touches the floor.
SceneDescription pressed_cube(double depth, const Eigen::Vector3d& gravity) {
  SceneDescription scene;
  scene.sim.gravity = gravity;
  BodyDescription floor =
      testing::rigid_box("floor", BodyType::kKinematic, {0.2, 0.2, 0.02}, {0, 0, -0.01});
  BodyDescription cube =
      testing::rigid_box("cube", BodyType::kAffine, {0.02, 0.02, 0.02}, {0, 0, 0.0115});
  cube.drive_stiffness = kStiffness;
  cube.script.keyframes = {{0.0, cube.pose}, {0.1, cube.pose}};
  cube.script.keyframes[1].pose.position.z() -= depth;
  scene.bodies = {floor, cube};
  return scene;
}

TEST(DrivenBody, PressedOnAWallPushesWithItsSpringsForce) {
  // The target ends 1 mm below where the cube's face would meet the floor's.
  Environment env(Model::build(pressed_cube(2.5e-3, Eigen::Vector3d::Zero())));
  testing::run_checked(env, 60);
  const double lag = env.center_of_mass(1).z() - env.state().poses[1].position.z();
  EXPECT_GT(lag, 1e-3);  // stopped by the floor (within d_hat of it), not at its target
  EXPECT_NEAR(pair_force(env), kStiffness * lag, 0.01 * kStiffness * lag);
}

TEST(DrivenBody, ItsDriveCarriesItsWeight) {
  Environment env(Model::build(pressed_cube(0.0, Eigen::Vector3d(0, 0, -9.81))));
  testing::run_checked(env, 30);
  // Held by its drive above the floor: no contact, no sag.
  EXPECT_EQ(pair_force(env), 0.0);
  EXPECT_NEAR(env.center_of_mass(1).z(), 0.0115, 1e-9);
}

TEST(DrivenBody, BodiesOfOneGroupNeverTouch) {
  SceneDescription scene = pressed_cube(0.0, Eigen::Vector3d::Zero());
  // A second cube overlapping the first: an intersecting start unless both are in one group.
  BodyDescription twin = scene.bodies[1];
  twin.name = "twin";
  twin.pose.position.x() += 0.01;
  twin.script.keyframes.clear();
  scene.bodies.push_back(twin);
  {
    Environment env(Model::build(scene));
    EXPECT_FALSE(env.step());
  }
  scene.bodies[1].collision_group = scene.bodies[2].collision_group = 3;
  Environment env(Model::build(scene));
  EXPECT_TRUE(env.step()) << env.failure();
}

}  // namespace
}  // namespace grip::solver
