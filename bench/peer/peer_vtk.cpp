#include "bench/peer/peer_vtk.hpp"

#include <vector>

#include "src/metrics/von_mises.hpp"
#include "src/trial/parallel_trial_scene.hpp"
#include "src/trial/trial.hpp"
#include "src/trial/vtk_series.hpp"

namespace grip::bench {
namespace {

constexpr int kClosingFrames = 4;

geometry::Vertices placed(const geometry::Vertices& local, const Eigen::Isometry3d& pose) {
  geometry::Vertices world(local.rows(), 3);
  for (Eigen::Index v = 0; v < local.rows(); ++v) {
    world.row(v) = (pose * local.row(v).transpose()).transpose();
  }
  return world;
}

// The scene's bodies (the object, then the links with a surface) at MuJoCo's poses.
trial::BodyFrame mujoco_frame(const trial::HandTrialScene& scene, double time,
                              const std::vector<Eigen::Isometry3d>& links,
                              const Eigen::Isometry3d& object) {
  const solver::SceneDescription& description = scene.model()->scene();
  trial::BodyFrame frame;
  frame.time = time;
  frame.vertices.push_back(placed(description.bodies[0].vertices, object));
  const std::vector<grippers::KinematicLink>& tree = scene.kinematics().links();
  for (std::size_t l = 0; l < tree.size(); ++l) {
    if (tree[l].surface.triangles.rows() == 0) continue;
    frame.vertices.push_back(placed(tree[l].surface.vertices, links[l]));
  }
  frame.stress.assign(frame.vertices.size(), Eigen::VectorXd());
  return frame;
}

// The parallel scene's bodies at MuJoCo's state: the object at `object`; jaw j's rigid bodies
// (its jaw block, a rigid finger) at `jaws[j]`, its soft finger at `fingers[j]`, with the von
// Mises stress grip's formula gives MuJoCo's deformed tets.
trial::BodyFrame mujoco_jaws_frame(const trial::ParallelTrialScene& scene,
                                   const grippers::ParallelGripper& gripper, double time,
                                   const Eigen::Isometry3d& object,
                                   const std::array<Eigen::Isometry3d, 2>& jaws,
                                   const std::array<geometry::Vertices, 2>& fingers) {
  const std::vector<solver::BodyDescription>& bodies = scene.model()->scene().bodies;
  const std::size_t per_jaw = (bodies.size() - 1) / 2;  // 2: jaw and soft finger; 1: rigid
  trial::BodyFrame frame;
  frame.time = time;
  frame.vertices.push_back(placed(bodies[0].vertices, object));
  frame.stress.emplace_back();
  for (std::size_t b = 1; b < bodies.size(); ++b) {
    const std::size_t j = (b - 1) / per_jaw;
    const auto& body = scene.model()->bodies()[b];
    if (!body.kind->tets(body.local).empty()) {  // the soft finger: MuJoCo's flex moved its tets
      const grippers::FinRayFinger& finger = *gripper.soft_finger;
      frame.vertices.push_back(fingers[j]);
      frame.stress.push_back(metrics::von_mises_stress(
          finger.mesh, fingers[j], finger.material.youngs_modulus, finger.material.poisson_ratio));
    } else {
      frame.vertices.push_back(placed(bodies[b].vertices, jaws[j]));
      frame.stress.emplace_back();
    }
  }
  return frame;
}

// Fewer frames than a dataset's (they are not part of the simulation).
trial::TrialParameters recording_parameters(trial::TrialParameters p) {
  p.closing_frames = kClosingFrames;
  p.validation_frames = 6;
  return p;
}

// grip's trial of `grasp` in `recording` (a scene of recording_parameters), every body in its
// frames, as DIR/STEM_grip.pvd.
void write_grip_series(const std::filesystem::path& dir, const std::string& stem,
                       const trial::TrialScene& recording, const synth::HandGrasp& grasp,
                       int threads) {
  trial::TrialRunOptions options;
  options.threads = threads;
  options.trajectory = false;
  options.body_frames = true;
  synth::Candidate candidate;
  candidate.hands = {grasp};
  const trial::TrialOutcome grip = trial::run_trials(recording, {candidate}, options).front();
  trial::write_vtk_series(dir, stem + "_grip", *recording.model(), grip.body_frames);
}

}  // namespace

void write_peer_jaws_vtk(const std::filesystem::path& dir, const std::string& stem,
                         const trial::TrialObject& object, const grippers::ParallelGripper& gripper,
                         const synth::HandGrasp& grasp, const MujocoOutcome& mujoco,
                         const trial::TrialParameters& parameters, int threads) {
  const trial::ParallelTrialScene recording(object, gripper, recording_parameters(parameters));
  write_grip_series(dir, stem, recording, grasp, threads);
  const std::vector<trial::BodyFrame> frames = {
      mujoco_jaws_frame(recording, gripper, 0.0, mujoco.object, mujoco.fingers,
                        mujoco.finger_vertices),
      mujoco_jaws_frame(recording, gripper, 1.0, mujoco.final_object, mujoco.final_fingers,
                        mujoco.final_finger_vertices)};
  trial::write_vtk_series(dir, stem + "_mujoco", *recording.model(), frames);
}

void write_peer_hand_vtk(const std::filesystem::path& dir, const std::string& stem,
                         const trial::TrialObject& object, const trial::HandTrialScene& scene,
                         const trial::HandTrialGrasp& grasp, const MujocoHandOutcome& mujoco,
                         int threads) {
  const trial::HandTrialScene recording(object, scene.hand(), scene.name(),
                                        recording_parameters(scene.parameters()));
  write_grip_series(dir, stem, recording, grasp, threads);
  const std::vector<trial::BodyFrame> frames = {
      mujoco_frame(scene, 0.0, mujoco.links, mujoco.object),
      mujoco_frame(scene, 1.0, mujoco.final_links, mujoco.final_object)};
  trial::write_vtk_series(dir, stem + "_mujoco", *scene.model(), frames);
}

}  // namespace grip::bench
