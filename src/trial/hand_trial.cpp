#include "src/trial/hand_trial.hpp"

#include <stdexcept>
#include <string>

namespace grip::trial {

namespace {

// A hand in the protocol: each finger's travel runs along its closing direction in joint space
// (HandTrialScene::closing_direction, fixed at the candidate) until one of its joints reaches
// a limit.
class HandTrialGripper final : public TrialGripper {
 public:
  HandTrialGripper(const HandTrialScene& scene, const std::vector<HandTrialGrasp>& grasps)
      : scene_(scene), grasps_(grasps) {
    const auto fingers = static_cast<int>(scene.fingers().size());
    for (std::size_t k = 0; k < grasps.size(); ++k) {
      try {
        scene.check(grasps[k]);
      } catch (const std::out_of_range& e) {
        throw std::out_of_range("candidate " + std::to_string(k) + ": " + e.what());
      }
      Path path;
      for (int f = 0; f < fingers; ++f) {
        path.direction.push_back(scene.closing_direction(grasps[k], f));
        path.travel.push_back(scene.closing_travel(grasps[k].joints, path.direction.back(), f));
      }
      paths_.push_back(std::move(path));
    }
  }

  const TrialParameters& parameters() const override { return scene_.parameters(); }
  const std::shared_ptr<const solver::Model>& model() const override { return scene_.model(); }
  bool soft_object() const override { return scene_.soft_object(); }
  int object_body() const override { return scene_.object_body(); }
  std::size_t candidate_count() const override { return grasps_.size(); }
  int finger_count() const override { return static_cast<int>(scene_.fingers().size()); }
  const std::vector<int>& finger_bodies(int finger) const override {
    return scene_.fingers()[static_cast<std::size_t>(finger)].bodies;
  }

  std::vector<double> place(solver::Environment& environment, std::size_t k) const override {
    scene_.place(environment, grasps_[k]);
    return paths_[k].travel;
  }

  void place_finger(solver::Environment& environment, std::size_t k, int finger, double from,
                    double to) const override {
    const Eigen::VectorXd& direction = paths_[k].direction[static_cast<std::size_t>(finger)];
    const Eigen::VectorXd& start = grasps_[k].joints;
    scene_.place_finger(environment, grasps_[k].pose, finger,
                        scene_.finger_joints(start, direction, finger, from),
                        scene_.finger_joints(start, direction, finger, to));
  }

  void move_finger(solver::Environment& environment, std::size_t k, int finger, double travel,
                   double speed) const override {
    const Eigen::VectorXd& direction = paths_[k].direction[static_cast<std::size_t>(finger)];
    const double next = travel + speed * scene_.parameters().sim.dt;
    scene_.move_finger(environment, grasps_[k].pose, finger,
                       scene_.finger_joints(grasps_[k].joints, direction, finger, next));
  }

  void hold_finger(solver::Environment& environment, int finger) const override {
    scene_.hold_finger(environment, finger);
  }

  bool driven_fingers() const override { return true; }

  const Eigen::Isometry3d& pose(std::size_t k) const override { return grasps_[k].pose; }

  std::vector<double> joints(std::size_t k, const std::vector<double>& travel) const override {
    Eigen::VectorXd q = grasps_[k].joints;
    for (int f = 0; f < finger_count(); ++f) {
      const Eigen::VectorXd finger =
          scene_.finger_joints(grasps_[k].joints, paths_[k].direction[static_cast<std::size_t>(f)],
                               f, travel[static_cast<std::size_t>(f)]);
      for (int dof : scene_.fingers()[static_cast<std::size_t>(f)].dofs) q[dof] = finger[dof];
    }
    return std::vector<double>(q.data(), q.data() + q.size());
  }

  geometry::Vertices surface_vertices(const solver::Environment& environment) const override {
    return scene_.hand_surface_vertices(environment);
  }
  std::array<double, 12> object_pose(const solver::Environment& environment) const override {
    return scene_.object_pose(environment);
  }
  metrics::DistanceMetrics grasp_distances(const solver::Environment& environment) const override {
    return scene_.grasp_distances(environment);
  }
  Eigen::VectorXd body_stress(const solver::Environment& environment, int body) const override {
    return scene_.body_stress(environment, body);
  }

 private:
  // Per finger: its closing direction in joint space and its longest travel (m).
  struct Path {
    std::vector<Eigen::VectorXd> direction;
    std::vector<double> travel;
  };

  const HandTrialScene& scene_;
  const std::vector<HandTrialGrasp>& grasps_;
  std::vector<Path> paths_;
};

}  // namespace

std::vector<TrialOutcome> run_hand_trials(const HandTrialScene& scene,
                                          const std::vector<HandTrialGrasp>& grasps,
                                          const TrialRunOptions& options) {
  return run_protocol(HandTrialGripper(scene, grasps), options);
}

}  // namespace grip::trial
