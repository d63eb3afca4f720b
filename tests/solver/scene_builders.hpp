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
