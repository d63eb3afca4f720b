// A parallel gripper's trial scene as the protocol sees it, with candidates placed
// (ParallelTrialScene::protocol_gripper).
#include "src/trial/parallel_trial_scene.hpp"
#include "src/trial/scene_trial_gripper.hpp"

#include <stdexcept>
#include <string>
#include <utility>

namespace grip::trial {

namespace {

using grippers::Jaw;
constexpr std::array<Jaw, 2> kJaws = {Jaw::kPositive, Jaw::kNegative};

// One or two parallel grippers in the protocol: each jaw is a finger whose travel runs along its
// gripper's closing axis, down to final_opening; a gripper's joint value is its opening.
// grasps[k][g] is candidate k's grasp for gripper g; finger f is jaw f % 2 of gripper f / 2.
class ParallelTrialGripper final : public SceneTrialGripper<ParallelTrialScene> {
 public:
  ParallelTrialGripper(const ParallelTrialScene& scene,
                       std::vector<std::vector<ParallelGrasp>> grasps)
      : SceneTrialGripper(scene), grasps_(std::move(grasps)) {
    for (const JawBodies& jaw : scene.jaws()) finger_bodies_.push_back({jaw.finger});
  }

  std::size_t candidate_count() const override { return grasps_.size(); }
  int finger_count() const override { return static_cast<int>(finger_bodies_.size()); }
  const std::vector<int>& finger_bodies(int finger) const override {
    return finger_bodies_[finger];
  }
  Eigen::VectorXd finger_stress(const solver::EnvironmentHandle& environment) const override {
    return scene_.finger_stress(environment);
  }

  std::vector<double> place(solver::EnvironmentHandle& environment, std::size_t k) const override {
    std::vector<double> travel;
    for (std::size_t g = 0; g < grasps_[k].size(); ++g) {
      scene_.place(environment, grasps_[k][g], static_cast<int>(g));
      const double half = 0.5 * (grasps_[k][g].opening - scene_.parameters().final_opening);
      travel.insert(travel.end(), {half, half});
    }
    return travel;
  }

  void place_finger(solver::EnvironmentHandle& environment, std::size_t k, int finger, double from,
                    double to) const override {
    scene_.advance_jaw(environment, grasp(k, finger), finger, to - from);
  }

  void move_finger(solver::EnvironmentHandle& environment, std::size_t k, int finger, double,
                   double speed) const override {
    solver::Script script;
    script.velocity = scene_.closing_velocity(grasp(k, finger), kJaws[finger % 2], speed);
    environment.set_script(scene_.jaws()[finger].jaw, script);
  }

  void hold_finger(solver::EnvironmentHandle& environment, int finger) const override {
    environment.set_script(scene_.jaws()[finger].jaw, solver::Script{});
  }

  std::vector<Eigen::Isometry3d> poses(std::size_t k) const override {
    std::vector<Eigen::Isometry3d> poses;
    for (const ParallelGrasp& g : grasps_[k]) poses.push_back(g.pose);
    return poses;
  }

  std::vector<double> joints(std::size_t k, const std::vector<double>& travel) const override {
    std::vector<double> openings;
    for (std::size_t g = 0; g < grasps_[k].size(); ++g) {
      openings.push_back(grasps_[k][g].opening - travel[2 * g] - travel[2 * g + 1]);
    }
    return openings;
  }

 private:
  const ParallelGrasp& grasp(std::size_t k, int finger) const {
    return grasps_[k][static_cast<std::size_t>(finger / 2)];
  }

  std::vector<std::vector<ParallelGrasp>> grasps_;
  std::vector<std::vector<int>> finger_bodies_;
};

}  // namespace

synth::Candidate parallel_candidate(const std::vector<ParallelGrasp>& grasps) {
  synth::Candidate candidate;
  for (const ParallelGrasp& grasp : grasps) {
    candidate.hands.push_back({grasp.pose, Eigen::VectorXd::Constant(1, grasp.opening), {}, {}});
  }
  return candidate;
}

std::unique_ptr<TrialGripper> ParallelTrialScene::protocol_gripper(
    const std::vector<synth::Candidate>& candidates) const {
  std::vector<std::vector<ParallelGrasp>> grasps;
  for (const synth::Candidate& candidate : candidates) {
    std::vector<ParallelGrasp>& each = grasps.emplace_back();
    for (const synth::HandGrasp& hand : candidate.hands)
      each.push_back({hand.pose, hand.joints[0]});
  }
  return std::make_unique<ParallelTrialGripper>(*this, std::move(grasps));
}

}  // namespace grip::trial
