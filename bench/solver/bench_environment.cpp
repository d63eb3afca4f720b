// One environment's cost per time step on the two shapes of problem a grasp trial has:
//  - a soft body of about 2,000 vertices pressed by a kinematic plate (the fin-ray case:
//    elasticity and the sparse factorization dominate), and
//  - an affine body resting on a kinematic mesh of about 20,000 triangles (the hand case:
//    contact queries dominate).
// Each benchmark iteration is one step; counters give Newton iterations and contacts per step.
// Run: build/bench/solver/bench_environment --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include "solver/environment.hpp"
#include "src/geometry/primitives.hpp"
#include "src/scene/primitives.hpp"

namespace grip::solver {
namespace {

// A 6 cm soft cube on 12 cells per side (13^3 = 2,197 vertices, 10,368 tets) on the ground,
// pressed by a plate coming down at 5 cm/s.
SceneDescription soft_body_in_contact() {
  SceneDescription scene;
  BodyDescription cube;
  cube.name = "cube";
  cube.type = BodyType::kFem;
  scene::set_fem_mesh(cube, scene::box_tets({0.06, 0.06, 0.06}, 0.005));
  cube.pose.position = {0, 0, 0.0305};
  cube.material.youngs = 1e5;
  scene.bodies.push_back(cube);
  scene.bodies.push_back(scene::surface_body("ground", BodyType::kKinematic,
                                             geometry::make_box({0.3, 0.3, 0.02}), {0, 0, -0.01}));
  BodyDescription plate = scene::surface_body("plate", BodyType::kKinematic,
                                              geometry::make_box({0.1, 0.1, 0.01}), {0, 0, 0.0665});
  plate.script.velocity = {0, 0, -0.05};
  scene.bodies.push_back(plate);
  return scene;
}

// A 4 cm affine cube resting on top of a kinematic sphere of 20,000 triangles.
SceneDescription affine_body_on_dense_mesh() {
  SceneDescription scene;
  const geometry::SurfaceMesh sphere = geometry::make_sphere(0.2, 100, 50);
  scene.bodies.push_back(scene::surface_body("sphere", BodyType::kKinematic, sphere, {0, 0, -0.2}));
  scene.bodies.push_back(scene::surface_body(
      "cube", BodyType::kAffine, geometry::make_box({0.04, 0.04, 0.04}), {0, 0, 0.0205}));
  return scene;
}

void step_scene(benchmark::State& state, const SceneDescription& scene) {
  Environment env(Model::build(scene));
  for (int s = 0; s < 3; ++s) env.step();  // into contact before timing
  double newton = 0.0;
  double steps = 0.0;
  for (auto _ : state) {
    if (!env.step()) {
      state.SkipWithError(env.failure().c_str());
      break;
    }
    newton += env.last_step().newton_iterations;
    steps += 1.0;
  }
  state.counters["newton_per_step"] = newton / std::max(1.0, steps);
  state.counters["dofs"] = env.model().dof_count();
  state.counters["collision_vertices"] = env.model().collision().size();
  state.counters["triangles"] = static_cast<double>(env.model().collision().faces.size());
}

void BM_SoftBodyInContact(benchmark::State& state) { step_scene(state, soft_body_in_contact()); }
void BM_AffineBodyOnDenseKinematicMesh(benchmark::State& state) {
  step_scene(state, affine_body_on_dense_mesh());
}

BENCHMARK(BM_SoftBodyInContact)->Unit(benchmark::kMillisecond)->Iterations(10);
BENCHMARK(BM_AffineBodyOnDenseKinematicMesh)->Unit(benchmark::kMillisecond)->Iterations(20);

}  // namespace
}  // namespace grip::solver

BENCHMARK_MAIN();
