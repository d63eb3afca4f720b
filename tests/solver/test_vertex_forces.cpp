// Per-vertex contact forces: on a box resting on the floor they balance its weight, and the
// floor takes the opposite; on a box held on a ramp by friction the friction force holds the
// downhill part of the weight.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tests/solver/scene_builders.hpp"

namespace grip::solver::testing {
namespace {

struct BodySums {
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  Eigen::Vector3d friction = Eigen::Vector3d::Zero();
};

BodySums sum_over_body(Environment& env, int body) {
  const VertexContactForces forces = env.vertex_contact_forces();
  const CollisionMesh& mesh = env.model().collision();
  BodySums sums;
  for (int i = 0; i < mesh.size(); ++i) {
    if (mesh.vertex_body[i] != body) continue;
    sums.normal += forces.normal.row(i).transpose();
    sums.friction += forces.friction.row(i).transpose();
  }
  return sums;
}

TEST(VertexContactForces, BalanceTheWeightOfARestingBox) {
  SceneDescription scene;
  scene.sim.gravity = Eigen::Vector3d(0, 0, -9.81);
  BodyDescription box = rigid_box("box", BodyType::kAffine, {0.04, 0.04, 0.04}, {0, 0, 0.0205});
  box.material.density = 800.0;
  scene.bodies = {rigid_box("floor", BodyType::kKinematic, {0.2, 0.2, 0.02}, {0, 0, -0.01}), box};
  Environment env(Model::build(scene));
  run_checked(env, 30);
  const double weight = 800.0 * 0.04 * 0.04 * 0.04 * 9.81;
  const BodySums on_box = sum_over_body(env, 1);
  const BodySums on_floor = sum_over_body(env, 0);
  EXPECT_NEAR(on_box.normal.z(), weight, 0.01 * weight);
  EXPECT_NEAR(on_box.normal.head<2>().norm(), 0.0, 1e-6 * weight);
  EXPECT_LT((on_box.normal + on_floor.normal).norm(), 1e-9 * weight);
  EXPECT_LT(on_box.friction.norm(), 1e-3 * weight);
}

TEST(VertexContactForces, FrictionHoldsABoxOnARamp) {
  const double theta = 20.0 * std::numbers::pi / 180.0;
  const SceneDescription scene = box_on_ramp(theta, 0.8, 500.0, 0.005);
  const Eigen::Quaterniond tilt(Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitY()));
  const Eigen::Vector3d normal = tilt * Eigen::Vector3d::UnitZ();
  Environment env(Model::build(scene));
  run_checked(env, 80);
  const double weight = 500.0 * 0.04 * 0.04 * 0.04 * 9.81;
  const BodySums on_box = sum_over_body(env, 1);
  // Normal force: the weight's component along the ramp normal; friction: its downhill part,
  // pointing uphill.
  EXPECT_NEAR(on_box.normal.dot(normal), weight * std::cos(theta), 0.02 * weight);
  const Eigen::Vector3d downhill = tilt * Eigen::Vector3d::UnitX();
  EXPECT_NEAR(on_box.friction.dot(-downhill), weight * std::sin(theta), 0.02 * weight);
}

}  // namespace
}  // namespace grip::solver::testing
