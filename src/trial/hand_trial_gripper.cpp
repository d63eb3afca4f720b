// A hand's trial scene as the protocol sees it, with candidates placed
// (HandTrialScene::protocol_gripper).
#include "src/trial/hand_trial_scene.hpp"
#include "src/trial/scene_trial_gripper.hpp"

#include <stdexcept>
#include <string>
#include <utility>

namespace grip::trial {

namespace {

// One or two hands in the protocol: each finger's travel runs along its closing direction in
// its hand's joint space (HandTrialScene::closing_direction, fixed at the candidate) until one
// of its joints reaches a limit. grasps[k][h] is candidate k's grasp for hand h.
class HandTrialGripper final : public SceneTrialGripper<HandTrialScene> {
 public:
  HandTrialGripper(const HandTrialScene& scene, std::vector<std::vector<HandTrialGrasp>> grasps)
      : SceneTrialGripper(scene), grasps_(std::move(grasps)) {
    const auto fingers = static_cast<int>(scene.fingers().size());
    for (std::size_t k = 0; k < grasps_.size(); ++k) {
      try {
        for (std::size_t h = 0; h < grasps_[k].size(); ++h) {
          scene.check(grasps_[k][h], static_cast<int>(h));
        }
      } catch (const std::out_of_range& e) {
        throw std::out_of_range("candidate " + std::to_string(k) + ": " + e.what());
      }
      Path path;
      for (int f = 0; f < fingers; ++f) {
        const HandTrialGrasp& grasp = finger_grasp(k, f);
        path.direction.push_back(scene.closing_direction(grasp, f));
        path.travel.push_back(scene.closing_travel(grasp.joints, path.direction.back(), f));
      }
      paths_.push_back(std::move(path));
    }
  }

  std::size_t candidate_count() const override { return grasps_.size(); }
  int finger_count() const override { return static_cast<int>(scene_.fingers().size()); }
  const std::vector<int>& finger_bodies(int finger) const override {
    return scene_.fingers()[static_cast<std::size_t>(finger)].bodies;
  }

  std::vector<double> place(solver::EnvironmentHandle& environment, std::size_t k) const override {
    for (std::size_t h = 0; h < grasps_[k].size(); ++h) {
      scene_.place(environment, grasps_[k][h], static_cast<int>(h));
    }
    return paths_[k].travel;
  }

  void place_finger(solver::EnvironmentHandle& environment, std::size_t k, int finger, double from,
                    double to) const override {
    const Eigen::VectorXd& direction = paths_[k].direction[static_cast<std::size_t>(finger)];
    const HandTrialGrasp& grasp = finger_grasp(k, finger);
    const Eigen::VectorXd& start = grasp.joints;
    scene_.place_finger(environment, grasp.pose, finger,
                        scene_.finger_joints(start, direction, finger, from),
                        scene_.finger_joints(start, direction, finger, to));
  }

  void move_finger(solver::EnvironmentHandle& environment, std::size_t k, int finger, double travel,
                   double speed) const override {
    const Eigen::VectorXd& direction = paths_[k].direction[static_cast<std::size_t>(finger)];
    const double next = travel + speed * scene_.parameters().sim.dt;
    const HandTrialGrasp& grasp = finger_grasp(k, finger);
    scene_.move_finger(environment, grasp.pose, finger,
                       scene_.finger_joints(grasp.joints, direction, finger, next));
  }

  void hold_finger(solver::EnvironmentHandle& environment, int finger) const override {
    scene_.hold_finger(environment, finger);
  }

  bool driven_fingers() const override { return true; }

  std::vector<Eigen::Isometry3d> poses(std::size_t k) const override {
    std::vector<Eigen::Isometry3d> poses;
    for (const HandTrialGrasp& grasp : grasps_[k]) poses.push_back(grasp.pose);
    return poses;
  }

  std::vector<double> joints(std::size_t k, const std::vector<double>& travel) const override {
    std::vector<Eigen::VectorXd> q;
    for (const HandTrialGrasp& grasp : grasps_[k]) q.push_back(grasp.joints);
    for (int f = 0; f < finger_count(); ++f) {
      const HandFinger& finger = scene_.fingers()[static_cast<std::size_t>(f)];
      const Eigen::VectorXd moved = scene_.finger_joints(
          finger_grasp(k, f).joints, paths_[k].direction[static_cast<std::size_t>(f)], f,
          travel[static_cast<std::size_t>(f)]);
      Eigen::VectorXd& own = q[static_cast<std::size_t>(finger.hand)];
      for (int dof : finger.dofs) own[dof] = moved[dof];
    }
    std::vector<double> values;
    for (const Eigen::VectorXd& hand : q)
      values.insert(values.end(), hand.data(), hand.data() + hand.size());
    return values;
  }

 private:
  // Per finger: its closing direction in joint space and its longest travel (m).
  struct Path {
    std::vector<Eigen::VectorXd> direction;
    std::vector<double> travel;
  };

  const HandTrialGrasp& finger_grasp(std::size_t k, int finger) const {
    const int hand = scene_.fingers()[static_cast<std::size_t>(finger)].hand;
    return grasps_[k][static_cast<std::size_t>(hand)];
  }

  std::vector<std::vector<HandTrialGrasp>> grasps_;
  std::vector<Path> paths_;
};

}  // namespace

std::unique_ptr<TrialGripper> HandTrialScene::protocol_gripper(
    const std::vector<synth::Candidate>& candidates) const {
  std::vector<std::vector<HandTrialGrasp>> grasps;
  for (const synth::Candidate& candidate : candidates) grasps.push_back(candidate.hands);
  return std::make_unique<HandTrialGripper>(*this, std::move(grasps));
}

}  // namespace grip::trial
