#include "bench/accuracy/accuracy_scenes.hpp"

#include <chrono>
#include <cmath>
#include <ctime>
#include <stdexcept>

#include "src/geometry/boundary_surface.hpp"
#include "src/geometry/primitives.hpp"
#include "src/grippers/coarse_leap_hand.hpp"
#include "src/grippers/parallel_gripper.hpp"
#include "src/scene/primitives.hpp"
#include "src/synth/prepared_object.hpp"
#include "src/synth/synthesize.hpp"
#include "src/trial/hand_trial_scene.hpp"
#include "src/trial/parallel_trial_scene.hpp"
#include "src/trial/trial.hpp"

namespace grip::bench {
namespace {

template <class Run>
SceneRun timed(Run&& run) {
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpu_start = std::clock();
  SceneRun result;
  result.outcomes = run();
  result.cpu_seconds = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

// What every scene shortens: 4 steps per gravity phase at the default dt (phase_duration a
// multiple of every swept dt), only the frames the errors compare (the settled grasp and one
// frame at the end of each gravity phase) and fewer D1/D2 points.
trial::TrialParameters reduced() {
  trial::TrialParameters p;
  p.phase_duration = 0.04;
  p.closing_frames = 2;
  p.validation_frames = 6;
  p.metric_samples = 5000;
  return p;
}

// The 80 mm fin-ray gripper with `layers` tet layers across the finger's depth (4 in its own
// mesh): the scenes' hand-made grasps are placed for its length.
grippers::ParallelGripper fin_ray(double layers) {
  grippers::FinRayOptions options = grippers::fin_ray_80mm_options();
  options.layers = static_cast<int>(std::lround(layers));
  return grippers::make_umi_soft_gripper(options);
}

// Fin-ray fingers squeeze at 2 cm/s, as in the trial's tests, and close at most 3 mm past the
// object per jaw (the tests: 7.5 mm; they wrap it before 50 N either way).
trial::TrialParameters fin_ray_parameters(double width) {
  trial::TrialParameters p = reduced();
  p.squeeze_speed = 0.02;
  p.final_opening = width - 0.006;
  return p;
}

// A parallel grasp with the gripper's origin at `at` (gripper frame = world otherwise; the
// fingers extend along +z, the jaws close along y) and the jaws open 4.6 mm beyond `width`.
synth::Candidate parallel_grasp(const Eigen::Vector3d& at, double width) {
  trial::ParallelGrasp grasp;
  grasp.pose.translation() = at;
  grasp.opening = width + 0.0046;
  return trial::parallel_candidate({grasp});
}

AccuracyScene fin_ray_rigid() {
  AccuracyScene scene;
  scene.name = "fin-ray x rigid";
  scene.setup =
      "80 mm fin-ray fingers; rigid cylinder r 2 cm, 3 cm long along the approach axis, mu 1 "
      "(3.5 on the fingers), "
      "3 hand-made candidates (centred; fingertips only; 1.5 cm off-centre across the fingers)";
  scene.parameters = fin_ray_parameters(0.04);
  scene.mesh_setting = "fin-ray tet layers";
  // The 80 mm finger's own mesh has 4 layers; this scene's default keeps the benchmark
  // affordable, and the sweep measures every count against 8.
  scene.mesh_values = {1, 2, 3, 4, 6, 8};
  scene.default_mesh = 1;
  scene.run = [](const trial::TrialParameters& p, double layers, int threads) {
    trial::TrialObject object;
    object.name = "cylinder";
    object.surface = geometry::make_cylinder(0.02, 0.03, 24);
    object.material.density = 500.0;
    object.material.friction = 1.0;
    const trial::ParallelTrialScene scene(object, fin_ray(layers), p);
    const std::vector<synth::Candidate> grasps = {parallel_grasp({0.0, 0.0, -0.05}, 0.04),
                                                  parallel_grasp({0.0, 0.0, -0.085}, 0.04),
                                                  parallel_grasp({0.015, 0.0, -0.05}, 0.04)};
    trial::TrialRunOptions options;
    options.threads = threads;
    return timed([&] { return trial::run_trials(scene, grasps, options); });
  };
  return scene;
}

AccuracyScene fin_ray_soft() {
  AccuracyScene scene;
  scene.name = "fin-ray x soft";
  scene.setup =
      "80 mm fin-ray fingers; soft box 6 x 3 x 2 cm (E 1 MPa, nu 0.4, mu 0.5), structured tets, "
      "3 hand-made candidates (centred; 2 cm towards one end; fingertips only)";
  scene.parameters = fin_ray_parameters(0.03);
  scene.mesh_setting = "object tet cell (m)";
  scene.mesh_values = {0.01, 0.005, 0.02 / 6};
  scene.default_mesh = 0.005;
  scene.run = [](const trial::TrialParameters& p, double cell, int threads) {
    trial::TrialObject object;
    object.name = "soft box";
    object.tets = scene::box_tets(Eigen::Vector3d(0.06, 0.03, 0.02), cell);
    object.surface = geometry::boundary_surface(*object.tets);
    object.material = {500.0, 1e6, 0.4, 0.5};
    const trial::ParallelTrialScene scene(object, fin_ray(1), p);
    const std::vector<synth::Candidate> grasps = {parallel_grasp({0.0, 0.0, -0.05}, 0.03),
                                                  parallel_grasp({0.02, 0.0, -0.05}, 0.03),
                                                  parallel_grasp({0.0, 0.0, -0.08}, 0.03)};
    trial::TrialRunOptions options;
    options.threads = threads;
    return timed([&] { return trial::run_trials(scene, grasps, options); });
  };
  return scene;
}

// The hand with 8-sided capsule links (as the hand trial's tests use it), so that a trial step
// costs a fraction of the full hand's.
const grippers::HandModel& coarse_leap() {
  static const grippers::HandModel hand = grippers::coarse_leap_hand();
  return hand;
}

// Two candidates synthesized on the cylinder (300 annealing steps, seed 1), as the hand trial's
// tests make them: the first one's fingers touch one after the other, the second's all close.
const std::vector<synth::Candidate>& hand_grasps(const geometry::SurfaceMesh& cylinder) {
  static const std::vector<synth::Candidate> grasps = [&] {
    synth::SynthesisParams params;
    params.hand.steps = 300;
    const synth::PreparedObject object(cylinder);
    return synth::synthesize(object, grippers::gripper_type(grippers::GripperKind::kLeap), false,
                             params, 1, 2)
        .candidates;
  }();
  return grasps;
}

// No mesh sweep: neither the hand's links nor the rigid object have a mesh to refine that the
// synthesized candidates would not depend on.
AccuracyScene hand_rigid() {
  AccuracyScene scene;
  scene.name = "hand x rigid";
  scene.setup =
      "rigid cylinder r 3 cm, 8 cm long, 16 sides, mu 1; LEAP hand with 8-sided capsule links; "
      "2 candidates synthesized on it (300 steps, seed 1); placed near the object, then closing at "
      "1 cm/s";
  scene.parameters = reduced();
  scene.mesh_setting = "none";
  scene.run = [](const trial::TrialParameters& p, double, int threads) {
    trial::TrialObject object;
    object.name = "cylinder";
    object.surface = geometry::make_cylinder(0.03, 0.08, 16);
    object.material.density = 500.0;
    object.material.friction = 1.0;
    const trial::HandTrialScene scene(object, coarse_leap(), "leap", p);
    const std::vector<synth::Candidate>& grasps = hand_grasps(object.surface);
    trial::TrialRunOptions options;
    options.threads = threads;
    return timed([&] { return trial::run_trials(scene, grasps, options); });
  };
  return scene;
}

}  // namespace

std::vector<std::string> standard_scene_names() {
  return {"fin-ray-rigid", "fin-ray-soft", "hand-rigid"};
}

std::vector<AccuracyScene> standard_scenes(const std::vector<std::string>& names) {
  std::vector<AccuracyScene> scenes;
  for (const std::string& name : names) {
    if (name == "fin-ray-rigid") {
      scenes.push_back(fin_ray_rigid());
    } else if (name == "fin-ray-soft") {
      scenes.push_back(fin_ray_soft());
    } else if (name == "hand-rigid") {
      scenes.push_back(hand_rigid());
    } else if (name == "bimanual") {
      throw std::invalid_argument(
          "grip bench accuracy: there is no bimanual trial scene (the trial protocol runs one "
          "gripper or one hand per candidate)");
    } else {
      throw std::invalid_argument("grip bench accuracy: unknown scene '" + name +
                                  "' (fin-ray-rigid, fin-ray-soft, hand-rigid)");
    }
  }
  return scenes;
}

}  // namespace grip::bench
