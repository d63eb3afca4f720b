// An FEM body whose own surface lies within d_hat of itself at rest (a wall thinner than d_hat,
// fine triangles at a rim): no barrier acts between those pairs, so the body keeps its rest
// shape; CCD still watches them, and contact with other bodies is unchanged.
#include <gtest/gtest.h>

#include <memory>

#include "tests/solver/scene_builders.hpp"

namespace grip::solver::testing {
namespace {

// A 4 cm square sheet 0.6 mm thick: its top and bottom faces are within d_hat (1 mm).
BodyDescription thin_sheet(const Eigen::Vector3d& position) {
  return soft_box("sheet", {0.04, 0.04, 6e-4}, 0.01, position, 1e5);
}

TEST(RestProximity, OnlyPairsWithinDhatAtRestAreListed) {
  SceneDescription sheet;
  sheet.bodies.push_back(thin_sheet({0, 0, 0}));
  // The model is kept: a reference into a temporary's collision mesh would dangle (ASan).
  const std::shared_ptr<const Model> sheet_model = Model::build(sheet);
  const CollisionMesh& near = sheet_model->collision();
  EXPECT_GT(near.point_triangle_near_at_rest.size(), 0u);
  EXPECT_GT(near.edge_edge_near_at_rest.size(), 0u);
  EXPECT_TRUE(std::is_sorted(near.point_triangle_near_at_rest.begin(),
                             near.point_triangle_near_at_rest.end()));

  // A 4 cm cube meshed at 1 cm has no surface pair closer than 1 cm apart from neighbours.
  SceneDescription cube;
  cube.bodies.push_back(soft_box("cube", {0.04, 0.04, 0.04}, 0.01, {0, 0, 0}, 1e5));
  const std::shared_ptr<const Model> cube_model = Model::build(cube);
  const CollisionMesh& apart = cube_model->collision();
  EXPECT_TRUE(apart.point_triangle_near_at_rest.empty());
  EXPECT_TRUE(apart.edge_edge_near_at_rest.empty());
}

// Falling freely, the sheet keeps its rest shape exactly: had the barrier acted between its
// faces, it would push them apart from the first step.
TEST(RestProximity, AThinSheetFallsWithoutSwelling) {
  SceneDescription scene;
  scene.sim.gravity = Eigen::Vector3d(0.0, 0.0, -9.81);
  scene.bodies.push_back(thin_sheet({0, 0, 1}));
  Environment env(Model::build(scene));
  run_checked(env, 20, [&](int s) {
    EXPECT_NEAR(env.min_volume_ratio(), 1.0, 1e-9) << "step " << s;
    EXPECT_EQ(env.last_step().retries, 0) << "step " << s;
  });
}

// Dropped onto a floor, the sheet lands and comes to rest on it: contact between bodies acts
// as before, every step converges without a retry, nothing intersects or inverts.
TEST(RestProximity, AThinSheetLandsOnAFloor) {
  SceneDescription scene;
  scene.sim.gravity = Eigen::Vector3d(0.0, 0.0, -9.81);
  scene.bodies.push_back(rigid_box("floor", BodyType::kKinematic, {0.2, 0.2, 0.02}, {0, 0, -0.01}));
  scene.bodies.push_back(thin_sheet({0, 0, 3e-3}));
  Environment env(Model::build(scene));
  run_checked(env, 60, [&](int s) { EXPECT_EQ(env.last_step().retries, 0) << "step " << s; });
  // At rest on the floor: within d_hat of it, above it, and still.
  EXPECT_GT(env.center_of_mass(1).z(), 3e-4);
  EXPECT_LT(env.center_of_mass(1).z(), 3e-4 + 1e-3);
  EXPECT_LT(env.center_of_mass_velocity(1).norm(), 1e-3);
}

}  // namespace
}  // namespace grip::solver::testing
