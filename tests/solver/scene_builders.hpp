#pragma once
// Small scenes for the solver's physics tests, and a stepping loop that checks the exact
// invariants (positive distances, positive volumes, no intersection) after every step.
#include <gtest/gtest.h>

#include "solver/environment.hpp"
#include "src/geometry/primitives.hpp"
#include "src/scene/invariants.hpp"
#include "src/scene/primitives.hpp"

namespace grip::solver::testing {

inline BodyDescription rigid_box(const std::string& name, BodyType type,
                                 const Eigen::Vector3d& size, const Eigen::Vector3d& position) {
  const geometry::SurfaceMesh box = geometry::make_box(size);
  BodyDescription body;
  body.name = name;
  body.type = type;
  body.vertices = box.vertices;
  body.triangles = box.triangles;
  body.pose.position = position;
  return body;
}

inline BodyDescription soft_box(const std::string& name, const Eigen::Vector3d& size, double cell,
                                const Eigen::Vector3d& position, double youngs) {
  BodyDescription body;
  body.name = name;
  body.type = BodyType::kFem;
  scene::set_fem_mesh(body, scene::box_tets(size, cell));
  body.pose.position = position;
  body.material.youngs = youngs;
  body.material.poisson = 0.4;
  return body;
}

// A 2 cm affine cube pulled by a drive of `stiffness` (N/m) towards its script's pose (here
// its start pose): a driven body, as a hand's link.
inline BodyDescription driven_cube(const std::string& name, const Eigen::Vector3d& position,
                                   double stiffness) {
  BodyDescription cube = rigid_box(name, BodyType::kAffine, {0.02, 0.02, 0.02}, position);
  cube.drive_stiffness = stiffness;
  cube.script.keyframes = {{0.0, cube.pose}, {0.1, cube.pose}};
  return cube;
}

// One body of each kind: a kinematic floor rising 1 cm in 0.1 s, a soft box, an affine box and
// a driven cube, so that affine DOFs come after FEM ones; for the data-parallel engine's tests.
inline SceneDescription every_kind_of_body() {
  SceneDescription scene;
  BodyDescription floor = rigid_box("floor", BodyType::kKinematic, {0.3, 0.3, 0.02}, {0, 0, -0.01});
  floor.script.keyframes = {{0.0, floor.pose}, {0.1, floor.pose}};
  floor.script.keyframes[1].pose.position.z() += 0.01;
  BodyDescription box = rigid_box("box", BodyType::kAffine, {0.04, 0.03, 0.02}, {0.0, 0.0, 0.1});
  box.material.density = 800.0;
  scene.bodies = {floor, soft_box("soft", {0.03, 0.02, 0.02}, 0.01, {0.1, 0, 0.05}, 2e5), box,
                  driven_cube("link", {-0.1, 0, 0.05}, 2e4)};
  return scene;
}

// A 4 cm affine box resting on a kinematic ramp tilted by theta about y (gravity along -z),
// 0.2 mm above the reach of the barrier so it settles onto it. Body 0 is the ramp, body 1 the
// box; downhill is tilt * x.
inline SceneDescription box_on_ramp(double theta, double mu, double density, double dt) {
  SceneDescription scene;
  scene.sim.gravity = Eigen::Vector3d(0, 0, -9.81);
  scene.sim.dt = dt;
  const Eigen::Quaterniond tilt(Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitY()));
  const Eigen::Vector3d normal = tilt * Eigen::Vector3d::UnitZ();
  BodyDescription ramp = rigid_box("ramp", BodyType::kKinematic, {2.0, 0.5, 0.02}, -0.01 * normal);
  ramp.pose.rotation = tilt;
  ramp.material.friction = mu;
  BodyDescription box =
      rigid_box("box", BodyType::kAffine, {0.04, 0.04, 0.04}, (0.02 + 1.2e-3) * normal);
  box.pose.rotation = tilt;
  box.material.friction = mu;
  box.material.density = density;
  scene.bodies = {ramp, box};
  return scene;
}

// Steps `steps` times; after each step checks that the step succeeded, that every contact
// distance is positive, that no tet is inverted and that no surfaces intersect (exactly).
// `each` runs after every step for test-specific checks.
template <typename Each>
void run_checked(Environment& env, int steps, Each each) {
  for (int s = 0; s < steps; ++s) {
    ASSERT_TRUE(env.step()) << env.failure();
    const StepDiagnostics& d = env.last_step();
    ASSERT_GT(d.min_distance, 0.0) << "step " << s;
    ASSERT_GT(d.min_volume_ratio, 0.0) << "step " << s;
    ASSERT_EQ(scene::count_intersections(env), 0) << "step " << s;
    each(s);
  }
}

inline void run_checked(Environment& env, int steps) {
  run_checked(env, steps, [](int) {});
}

}  // namespace grip::solver::testing
