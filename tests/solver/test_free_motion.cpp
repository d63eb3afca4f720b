// Bodies without contact: implicit Euler's closed form, momentum, orthogonality; bodies held
// still by Environment::hold and falling again once released.
#include <gtest/gtest.h>

#include <stdexcept>

#include "solver/kernels/affine_body.hpp"
#include "tests/solver/scene_builders.hpp"

namespace grip::solver::testing {
namespace {

// Implicit Euler under constant gravity: v_n = v_0 + n h g, x_n = x_0 + h sum_{k=1..n} v_k.
Eigen::Vector3d implicit_euler_position(const Eigen::Vector3d& x0, const Eigen::Vector3d& v0,
                                        const Eigen::Vector3d& g, double h, int n) {
  return x0 + h * (n * v0 + h * g * (n * (n + 1) / 2.0));
}

TEST(FreeMotion, AffineFreeFallMatchesImplicitEulerClosedForm) {
  SceneDescription scene;
  scene.sim.gravity = Eigen::Vector3d(0.0, 0.0, -9.81);
  scene.bodies.push_back(rigid_box("box", BodyType::kAffine, {0.1, 0.2, 0.05}, {0, 0, 1}));
  scene.bodies[0].velocity = Eigen::Vector3d(0.3, 0.0, 2.0);
  Environment env(Model::build(scene));
  const Eigen::Vector3d x0 = env.center_of_mass(0);
  run_checked(env, 50, [&](int s) {
    const Eigen::Vector3d expected =
        implicit_euler_position(x0, {0.3, 0.0, 2.0}, scene.sim.gravity, scene.sim.dt, s + 1);
    EXPECT_LT((env.center_of_mass(0) - expected).norm(), 1e-9) << "step " << s;
    EXPECT_LT((env.rotation(0) - Eigen::Matrix3d::Identity()).norm(), 1e-9);
  });
}

TEST(FreeMotion, SoftFreeFallMatchesTheClosedFormWithoutDeforming) {
  SceneDescription scene;
  scene.sim.gravity = Eigen::Vector3d(0.0, -9.81, 0.0);
  scene.bodies.push_back(soft_box("jelly", {0.04, 0.04, 0.04}, 0.02, {0, 0, 0}, 1e5));
  Environment env(Model::build(scene));
  const Eigen::Vector3d x0 = env.center_of_mass(0);
  run_checked(env, 30, [&](int s) {
    const Eigen::Vector3d expected = implicit_euler_position(
        x0, Eigen::Vector3d::Zero(), scene.sim.gravity, scene.sim.dt, s + 1);
    EXPECT_LT((env.center_of_mass(0) - expected).norm(), 1e-9) << "step " << s;
    EXPECT_NEAR(env.min_volume_ratio(), 1.0, 1e-9);
  });
}

TEST(FreeMotion, SpinningAffineBodyKeepsMomentumAndStaysNearlyOrthogonal) {
  SceneDescription scene;
  scene.sim.gravity.setZero();
  scene.bodies.push_back(rigid_box("spinner", BodyType::kAffine, {0.1, 0.04, 0.02}, {0, 0, 0}));
  const Eigen::Vector3d velocity(0.1, -0.2, 0.05);
  scene.bodies[0].velocity = velocity;
  scene.bodies[0].angular_velocity = Eigen::Vector3d(0.5, 1.0, 4.0);
  Environment env(Model::build(scene));
  const Eigen::Vector3d x0 = env.center_of_mass(0);
  const BodyModel& body = env.model().bodies()[0];
  run_checked(env, 100, [&](int s) {
    // Linear momentum: the centre of mass moves uniformly.
    EXPECT_LT((env.center_of_mass_velocity(0) - velocity).norm(), 1e-9) << "step " << s;
    EXPECT_LT((env.center_of_mass(0) - (x0 + (s + 1) * scene.sim.dt * velocity)).norm(), 1e-9);
    const Eigen::Matrix3d a = kernels::affine_body_matrix(env.dofs().segment<12>(body.dof_offset));
    EXPECT_LT((a * a.transpose() - Eigen::Matrix3d::Identity()).norm(), 1e-3) << "step " << s;
  });
  // It did turn: a quarter turn and more about z in one second.
  EXPECT_LT(env.rotation(0)(0, 0), 0.5);
}

// Held, a body stays put under gravity; released, it falls from rest by implicit Euler's closed
// form. An FEM body held by its central tet sags around it but its centre stays within the
// sag; holding a kinematic body is refused.
TEST(FreeMotion, HeldBodiesStayAndReleasedOnesFall) {
  SceneDescription scene;
  scene.sim.gravity = Eigen::Vector3d(0.0, 0.0, -9.81);
  scene.bodies.push_back(rigid_box("box", BodyType::kAffine, {0.1, 0.2, 0.05}, {0, 0, 1}));
  scene.bodies.push_back(soft_box("jelly", {0.04, 0.04, 0.04}, 0.01, {0.5, 0, 1}, 1e5));
  scene.bodies.push_back(rigid_box("plate", BodyType::kKinematic, {0.1, 0.1, 0.01}, {-1, 0, 0}));
  Environment env(Model::build(scene));
  EXPECT_THROW(env.hold(2), std::invalid_argument);
  const Eigen::Vector3d box0 = env.center_of_mass(0), jelly0 = env.center_of_mass(1);
  env.hold(0);
  env.hold(1);
  run_checked(env, 20);
  EXPECT_EQ(env.center_of_mass(0), box0);
  EXPECT_EQ(env.center_of_mass_velocity(0), Eigen::Vector3d::Zero());
  // The jelly hangs from its central tet: it sags (its centre below where it was), but by far
  // less than the 2 cm a free fall covers in 0.2 s.
  const double sag = jelly0.z() - env.center_of_mass(1).z();
  EXPECT_GT(sag, 0.0);
  EXPECT_LT(sag, 2e-3);
  env.release(0);
  run_checked(env, 10, [&](int s) {
    const Eigen::Vector3d expected = implicit_euler_position(
        box0, Eigen::Vector3d::Zero(), scene.sim.gravity, scene.sim.dt, s + 1);
    EXPECT_LT((env.center_of_mass(0) - expected).norm(), 1e-9) << "step " << s;
  });
  EXPECT_LT(jelly0.z() - env.center_of_mass(1).z(), 2e-3);  // still held
}

}  // namespace
}  // namespace grip::solver::testing
