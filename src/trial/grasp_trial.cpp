#include "src/trial/grasp_trial.hpp"

namespace grip::trial {

namespace {

using grippers::Jaw;
constexpr std::array<Jaw, 2> kJaws = {Jaw::kPositive, Jaw::kNegative};

// A parallel gripper in the protocol: each jaw is a finger whose travel runs along the
// candidate's closing axis, down to final_opening; the joint value is the opening.
class ParallelTrialGripper final : public TrialGripper {
 public:
  ParallelTrialGripper(const TrialScene& scene, const std::vector<ParallelGrasp>& grasps)
      : scene_(scene), grasps_(grasps) {
    for (int j = 0; j < 2; ++j) finger_bodies_[j] = {scene.jaws()[j].finger};
  }

  const TrialParameters& parameters() const override { return scene_.parameters(); }
  const std::shared_ptr<const solver::Model>& model() const override { return scene_.model(); }
  bool soft_object() const override { return scene_.soft_object(); }
  int object_body() const override { return scene_.object_body(); }
  std::size_t candidate_count() const override { return grasps_.size(); }
  int finger_count() const override { return 2; }
  const std::vector<int>& finger_bodies(int finger) const override {
    return finger_bodies_[finger];
  }

  std::vector<double> place(solver::Environment& environment, std::size_t k) const override {
    scene_.place(environment, grasps_[k]);
    const double travel = 0.5 * (grasps_[k].opening - scene_.parameters().final_opening);
    return {travel, travel};
  }

  void place_finger(solver::Environment& environment, std::size_t k, int finger, double from,
                    double to) const override {
    scene_.advance_jaw(environment, grasps_[k], finger, to - from);
  }

  void move_finger(solver::Environment& environment, std::size_t k, int finger, double,
                   double speed) const override {
    solver::Script script;
    script.velocity = scene_.closing_velocity(grasps_[k], kJaws[finger], speed);
    environment.set_script(scene_.jaws()[finger].jaw, script);
  }

  void hold_finger(solver::Environment& environment, int finger) const override {
    environment.set_script(scene_.jaws()[finger].jaw, solver::Script{});
  }

  const Eigen::Isometry3d& pose(std::size_t k) const override { return grasps_[k].pose; }

  std::vector<double> joints(std::size_t k, const std::vector<double>& travel) const override {
    return {grasps_[k].opening - travel[0] - travel[1]};
  }

  geometry::Vertices surface_vertices(const solver::Environment& environment) const override {
    return scene_.gripper_surface_vertices(environment);
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
  const TrialScene& scene_;
  const std::vector<ParallelGrasp>& grasps_;
  std::array<std::vector<int>, 2> finger_bodies_;
};

}  // namespace

std::vector<TrialOutcome> run_trials(const TrialScene& scene,
                                     const std::vector<ParallelGrasp>& grasps,
                                     const TrialRunOptions& options) {
  return run_protocol(ParallelTrialGripper(scene, grasps), options);
}

}  // namespace grip::trial
