#include "bench/peer/peer_vtk.hpp"

#include <vector>

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

}  // namespace

void write_peer_hand_vtk(const std::filesystem::path& dir, const std::string& stem,
                         const trial::TrialObject& object, const trial::HandTrialScene& scene,
                         const trial::HandTrialGrasp& grasp, const MujocoHandOutcome& mujoco,
                         int threads) {
  // Fewer frames than a dataset's (they are not part of the simulation).
  trial::TrialParameters p = scene.parameters();
  p.closing_frames = kClosingFrames;
  p.validation_frames = 6;
  const trial::HandTrialScene recording(object, scene.hand(), scene.name(), p);
  trial::TrialRunOptions options;
  options.threads = threads;
  options.trajectory = false;
  options.body_frames = true;
  synth::Candidate candidate;
  candidate.hands = {grasp};
  const trial::TrialOutcome grip = trial::run_trials(recording, {candidate}, options).front();
  trial::write_vtk_series(dir, stem + "_grip", *scene.model(), grip.body_frames);
  const std::vector<trial::BodyFrame> frames = {
      mujoco_frame(scene, 0.0, mujoco.links, mujoco.object),
      mujoco_frame(scene, 1.0, mujoco.final_links, mujoco.final_object)};
  trial::write_vtk_series(dir, stem + "_mujoco", *scene.model(), frames);
}

}  // namespace grip::bench
