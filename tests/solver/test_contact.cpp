// Hard contact cases: no tunnelling at high speed, no inversion under a hard squeeze, a stack
// with a large mass ratio, and a soft object held by friction alone (mu = 3.5).
#include <gtest/gtest.h>

#include "tests/solver/scene_builders.hpp"

namespace grip::solver::testing {
namespace {

TEST(Contact, FastSmallBodyDoesNotTunnelThroughAThinPlate) {
  SceneDescription scene;
  scene.sim.gravity.setZero();
  // A 1 mm plate and a 1 cm cube crossing 1 m per step (100 m/s at dt = 0.01 s).
  scene.bodies.push_back(rigid_box("plate", BodyType::kKinematic, {0.2, 0.2, 0.001}, {0, 0, 0}));
  scene.bodies.push_back(rigid_box("bullet", BodyType::kAffine, {0.01, 0.01, 0.01}, {0, 0, 0.05}));
  scene.bodies[1].velocity = Eigen::Vector3d(0, 0, -100.0);
  scene.bodies[1].material.density = 8000.0;
  Environment env(Model::build(scene));
  run_checked(env, 10, [&](int s) {
    // Every vertex of the bullet stays above the plate's top face.
    const Vertices x = env.body_vertices(1);
    EXPECT_GT(x.col(2).minCoeff(), 0.0005) << "step " << s;
  });
  // It stopped or bounced: it is not moving down any more.
  EXPECT_GT(env.center_of_mass_velocity(1).z(), -1.0);
}

TEST(Contact, SoftBodySqueezedHardNeitherInvertsNorIntersects) {
  SceneDescription scene;
  scene.sim.gravity.setZero();
  scene.sim.dt = 0.01;
  // A 4 cm soft cube between two plates that close at 0.5 m/s each for three steps: by 3 cm.
  scene.bodies.push_back(soft_box("cube", {0.04, 0.04, 0.04}, 0.01, {0, 0, 0}, 1e5));
  for (const double side : {-1.0, 1.0}) {
    BodyDescription plate = rigid_box(side < 0 ? "left" : "right", BodyType::kKinematic,
                                      {0.01, 0.1, 0.1}, {side * (0.025 + 0.0005), 0, 0});
    plate.script.velocity = Eigen::Vector3d(-side * 0.5, 0, 0);
    scene.bodies.push_back(plate);
  }
  Environment env(Model::build(scene));
  double smallest = 1.0;
  run_checked(env, 10, [&](int s) {
    smallest = std::min(smallest, env.min_volume_ratio());
    // The plates move as scripted: 0.5 m/s inward for three steps, then not at all.
    EXPECT_NEAR(env.center_of_mass_velocity(1).x(), s <= 2 ? 0.5 : 0.0, 1e-12);
    if (s == 2) {
      for (int b : {1, 2}) env.set_script(b, Script{});
    }
  });
  // The cube was really squeezed: to about half its width.
  const Vertices x = env.body_vertices(0);
  EXPECT_LT(x.col(0).maxCoeff() - x.col(0).minCoeff(), 0.025);
  EXPECT_GT(smallest, 0.0);
  EXPECT_LT(smallest, 0.8);
}

TEST(Contact, StackWithMassRatioOfAThousandStaysIntersectionFree) {
  SceneDescription scene;
  scene.sim.gravity = Eigen::Vector3d(0, 0, -9.81);
  scene.bodies.push_back(
      rigid_box("ground", BodyType::kKinematic, {1.0, 1.0, 0.02}, {0, 0, -0.01}));
  BodyDescription light = rigid_box("light", BodyType::kAffine, {0.05, 0.05, 0.02}, {0, 0, 0.0105});
  light.material.density = 10.0;
  BodyDescription heavy = rigid_box("heavy", BodyType::kAffine, {0.05, 0.05, 0.02}, {0, 0, 0.031});
  heavy.material.density = 10000.0;
  scene.bodies = {scene.bodies[0], light, heavy};
  Environment env(Model::build(scene));
  run_checked(env, 100);
  // Resting: the heavy box sits on the light one, which sits on the ground.
  EXPECT_NEAR(env.center_of_mass(1).z(), 0.01, 1.5e-3);
  EXPECT_NEAR(env.center_of_mass(2).z(), 0.03, 3e-3);
  EXPECT_LT(env.center_of_mass_velocity(2).norm(), 1e-2);
}

TEST(Contact, HighFrictionHoldsASoftSqueezedObjectAgainstGravity) {
  SceneDescription scene;
  scene.sim.gravity.setZero();
  scene.bodies.push_back(soft_box("object", {0.03, 0.03, 0.03}, 0.01, {0, 0, 0}, 1e5));
  for (const double side : {-1.0, 1.0}) {
    BodyDescription pad = rigid_box(side < 0 ? "left" : "right", BodyType::kKinematic,
                                    {0.01, 0.05, 0.05}, {side * (0.02 + 0.0005), 0, 0});
    pad.script.velocity = Eigen::Vector3d(-side * 0.1, 0, 0);
    pad.material.friction = 3.5;
    scene.bodies.push_back(pad);
  }
  scene.bodies[0].material.friction = 3.5;
  scene.bodies[0].material.density = 500.0;
  Environment env(Model::build(scene));
  // Close by 2 mm per side, then stop and turn gravity on.
  run_checked(env, 20, [&](int s) {
    if (s == 1) {
      for (int b : {1, 2}) env.set_script(b, Script{});
    }
  });
  const Eigen::Vector3d held = env.center_of_mass(0);
  env.set_gravity(Eigen::Vector3d(0, 0, -9.81));
  run_checked(env, 50);
  EXPECT_LT((env.center_of_mass(0) - held).norm(), 1e-3);
  EXPECT_LT(env.center_of_mass_velocity(0).norm(), 1e-3);
}

}  // namespace
}  // namespace grip::solver::testing
