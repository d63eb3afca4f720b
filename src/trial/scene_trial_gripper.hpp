#pragma once
// What every trial scene's TrialGripper answers alike, forwarded to the scene
// (ParallelTrialScene, HandTrialScene), which measures its own surface, object pose, D1/D2 and
// stress: a scene's TrialGripper adds how candidates place it and how its fingers move.
#include <array>
#include <memory>
#include <vector>

#include "src/trial/trial_protocol.hpp"

namespace grip::trial {

template <class Scene>
class SceneTrialGripper : public TrialGripper {
 public:
  explicit SceneTrialGripper(const Scene& scene) : scene_(scene) {}

  const TrialParameters& parameters() const override { return scene_.parameters(); }
  const std::shared_ptr<const solver::Model>& model() const override { return scene_.model(); }
  bool soft_object() const override { return scene_.soft_object(); }
  int object_body() const override { return scene_.object_body(); }

  geometry::Vertices surface_vertices(const solver::EnvironmentHandle& environment) const override {
    return scene_.surface_vertices(environment);
  }
  std::vector<BodyVertex> surface_sources() const override { return scene_.surface_sources(); }
  std::array<double, 12> object_pose(const solver::EnvironmentHandle& environment) const override {
    return scene_.object_pose(environment);
  }
  metrics::DistanceMetrics grasp_distances(
      const solver::EnvironmentHandle& environment) const override {
    return scene_.grasp_distances(environment);
  }
  std::vector<metrics::DistanceMetrics> gripper_distances(
      const solver::EnvironmentHandle& environment) const override {
    return scene_.gripper_distances(environment);
  }
  Eigen::VectorXd body_stress(const solver::EnvironmentHandle& environment,
                              int body) const override {
    return scene_.body_stress(environment, body);
  }

 protected:
  const Scene& scene_;
};

}  // namespace grip::trial
