#pragma once
// The grasp trial of a dexterous hand (the LEAP hand of trial::HandTrialScene) on a rigid object
// run in MuJoCo: the same links, object mesh, per-finger closing paths in joint space, grip
// force per finger, six-axis gravity test and grip's verdict rule (mujoco_available() says
// whether this build has MuJoCo).
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "bench/peer/mujoco_trial.hpp"
#include "src/geometry/mesh.hpp"
#include "src/trial/hand_trial_scene.hpp"
#include "src/trial/trial_parameters.hpp"

namespace grip::bench {

struct MujocoHandOutcome {
  // As MujocoOutcome's.
  std::string verdict;
  std::string message;
  bool settled = false;
  std::vector<double> closing_forces;  // N per finger (the scene's order) when settled
  double largest_slip = 0.0;           // m
  // World from link frame of every link of the hand's tree, and world from object frame: at the
  // settled grasp, and at the end of the trial (the last gravity phase run; the settled grasp's
  // when it did not settle).
  std::vector<Eigen::Isometry3d> links, final_links;
  Eigen::Isometry3d object = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d final_object = Eigen::Isometry3d::Identity();
  double deepest_penetration = 0.0;  // m, MujocoOutcome's
  double cpu_seconds = 0.0;
  double compile_cpu_seconds = 0.0;
};

// One trial: `object` (closed, outward, object frame = world at the start) of `density` and
// `friction` (both sides' friction, grip's combined pair mu), the hand of `scene` at the
// candidate `grasp`. Without MuJoCo: verdict "load_error".
MujocoHandOutcome run_mujoco_hand_trial(const geometry::SurfaceMesh& object, double density,
                                        double friction, const trial::HandTrialScene& scene,
                                        const trial::HandTrialGrasp& grasp,
                                        const trial::TrialParameters& parameters,
                                        const MujocoSettings& settings = {});

}  // namespace grip::bench
