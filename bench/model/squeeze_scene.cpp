#include "bench/model/squeeze_scene.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>

#include "src/geometry/boundary_surface.hpp"
#include "src/geometry/primitives.hpp"
#include "src/scene/primitives.hpp"

namespace grip::bench {
namespace {

constexpr double kPadDepth = 0.01;   // m, along the closing axis
constexpr double kPadHeight = 0.06;  // m, across it (the pads overhang the cube)
constexpr double kGravity = 9.81;    // m/s^2, along -z once the pads hold

solver::Pose at(const Eigen::Vector3d& position) {
  solver::Pose pose;
  pose.position = position;
  return pose;
}

void set_surface(solver::BodyDescription& body, const geometry::SurfaceMesh& surface) {
  body.vertices = surface.vertices;
  body.triangles = surface.triangles;
}

}  // namespace

SqueezeScene make_squeeze_scene(const SqueezeOptions& options) {
  solver::SceneDescription description;
  solver::Material material;
  material.friction = options.friction;
  material.youngs = options.stiff_youngs;
  const double half = 0.5 * options.object_size;

  SqueezeScene scene;
  solver::BodyDescription cube;
  cube.name = "cube";
  cube.material = material;
  const geometry::TetMesh cube_tets =
      scene::box_tets(Eigen::Vector3d::Constant(options.object_size), options.object_cell);
  Eigen::VectorXi to_tet;
  const geometry::SurfaceMesh cube_surface = geometry::boundary_surface(cube_tets, &to_tet);
  if (options.fem_object) {
    cube.type = solver::BodyType::kFem;
    scene::set_fem_mesh(cube, cube_tets);
    scene.object_surface = to_tet;
  } else {
    cube.type = solver::BodyType::kAffine;
    set_surface(cube, cube_surface);
    scene.object_surface = Eigen::VectorXi::LinSpaced(cube_surface.vertices.rows(), 0,
                                                      cube_surface.vertices.rows() - 1);
  }
  description.bodies.push_back(cube);

  // The pads, +x first. Their surface is the boundary of their tet mesh either way.
  const Eigen::Vector3d pad_size(kPadDepth, kPadHeight, kPadHeight);
  const geometry::TetMesh pad_tets = scene::box_tets(pad_size, options.pad_cell);
  const geometry::SurfaceMesh pad_surface = geometry::boundary_surface(pad_tets);
  std::vector<solver::BodyDescription> jaws;
  for (int j = 0; j < 2; ++j) {
    const double side = j == 0 ? 1.0 : -1.0;
    solver::BodyDescription pad;
    pad.name = j == 0 ? "pad+" : "pad-";
    pad.material = material;
    pad.pose = at({side * (half + options.gap + 0.5 * kPadDepth), 0.0, 0.0});
    if (options.fem_fingers) {
      pad.type = solver::BodyType::kFem;
      scene::set_fem_mesh(pad, pad_tets);
      solver::BodyDescription jaw;
      jaw.name = j == 0 ? "jaw+" : "jaw-";
      jaw.type = solver::BodyType::kKinematic;
      jaw.material = material;
      set_surface(jaw, geometry::make_box(pad_size));
      jaw.pose = at({side * (half + options.gap + 1.5 * kPadDepth), 0.0, 0.0});
      solver::Pin pin;
      pin.kinematic_body = static_cast<int>(3 + jaws.size());
      for (Eigen::Index v = 0; v < pad_tets.vertices.rows(); ++v) {
        if (side * pad_tets.vertices(v, 0) > 0.5 * kPadDepth - 1e-9) {
          pin.vertices.push_back(static_cast<int>(v));
        }
      }
      pad.pins.push_back(pin);
      jaws.push_back(jaw);
    } else {
      pad.type = solver::BodyType::kKinematic;
      set_surface(pad, pad_surface);
    }
    description.bodies.push_back(pad);
  }
  for (const solver::BodyDescription& jaw : jaws) description.bodies.push_back(jaw);
  if (options.ground) {
    solver::BodyDescription floor;
    floor.name = "floor";
    floor.type = solver::BodyType::kKinematic;
    floor.material = material;
    // No wider along x than the cube, so it stays clear of the pads.
    set_surface(floor, geometry::make_box(Eigen::Vector3d(options.object_size, 0.1, 0.01)));
    floor.pose = at({0.0, 0.0, -(half + options.gap + 0.005)});
    description.bodies.push_back(floor);
  }
  description.sim.gravity.setZero();
  scene.model = solver::Model::build(description);
  return scene;
}

double pad_force(const SqueezeScene& scene, const solver::Environment& environment, int pad) {
  for (const solver::PairForce& force : environment.last_step().contact_forces) {
    if (force.body_a == 0 && force.body_b == scene.pads[pad]) return force.normal_force;
  }
  return 0.0;
}

bool next_squeeze_step(const SqueezeOptions& options, const SqueezeScene& scene,
                       solver::Environment& environment, SqueezeProgress& progress) {
  for (int j = 0; j < 2; ++j) {
    const double force = pad_force(scene, environment, j);
    progress.stopped[j] = progress.stopped[j] || force >= options.stop_force;
  }
  const bool closing = progress.held == 0 && !(progress.stopped[0] && progress.stopped[1]) &&
                       progress.steps < options.max_closing_steps;
  if (!closing) {
    if (progress.held == options.hold_steps) return false;
    ++progress.held;
  }
  ++progress.steps;
  environment.set_gravity(closing ? Eigen::Vector3d::Zero() : Eigen::Vector3d(0, 0, -kGravity));
  for (int j = 0; j < 2; ++j) {
    // The scripted body: the pad itself, or the jaw block a FEM pad is pinned to.
    const int driven = options.fem_fingers ? 3 + j : scene.pads[j];
    solver::Script script;
    if (closing && !progress.stopped[j]) {
      script.velocity.x() = (j == 0 ? -1.0 : 1.0) * options.closing_speed;
    }
    environment.set_script(driven, script);
  }
  return true;
}

SqueezeResult squeeze_result(const SqueezeScene& scene, const solver::Environment& environment) {
  SqueezeResult result;
  result.failed = environment.failed();
  result.failure = environment.failure();
  const solver::Model& model = environment.model();
  result.free_dofs = model.dof_count() - static_cast<int>(std::count(model.prescribed().begin(),
                                                                     model.prescribed().end(), 1));
  result.newton_iterations = environment.statistics().newton_iterations;
  const solver::Vertices body = environment.body_vertices(0);
  result.object_surface.resize(scene.object_surface.size(), 3);
  for (Eigen::Index v = 0; v < scene.object_surface.size(); ++v) {
    result.object_surface.row(v) = body.row(scene.object_surface[v]);
  }
  result.center = environment.center_of_mass(0);
  result.rotation = environment.rotation(0);
  result.closing_force =
      0.5 * (pad_force(scene, environment, 0) + pad_force(scene, environment, 1));
  result.friction_contacts = environment.last_step().friction_contacts;
  result.dofs = environment.dofs();
  return result;
}

SqueezeResult run_squeeze(const SqueezeOptions& options, const SqueezeScene& scene,
                          const Eigen::Isometry3d& place, bool friction_terms_at_zero_mu) {
  solver::Environment environment(scene.model);
  environment.place(0, place);
  environment.set_policy({.friction_terms_at_zero_mu = friction_terms_at_zero_mu});
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpu_start = std::clock();
  SqueezeProgress progress;
  while (next_squeeze_step(options, scene, environment, progress) && environment.step()) {
  }
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double cpu_s = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  SqueezeResult result = squeeze_result(scene, environment);
  result.wall_s = wall_s;
  result.cpu_s = cpu_s;
  return result;
}

SqueezeError squeeze_error(const SqueezeResult& lean, const SqueezeResult& full) {
  SqueezeError error;
  error.center_m = (lean.center - full.center).norm();
  const double cosine = 0.5 * ((lean.rotation.transpose() * full.rotation).trace() - 1.0);
  error.rotation_rad = std::acos(std::clamp(cosine, -1.0, 1.0));
  error.vertex_m = (lean.object_surface - full.object_surface).rowwise().norm().maxCoeff();
  error.force_relative =
      full.closing_force > 0.0
          ? std::abs(lean.closing_force - full.closing_force) / full.closing_force
          : 0.0;
  return error;
}

}  // namespace grip::bench
