#pragma once
// D1/D2 of a rigid-jaw parallel gripper against a rigid object, both at given world poses, with
// the trial's own points and code (trial::TrialScene::grasp_distances): how `grip bench peer`
// measures another engine's settled grasp exactly as grip measures its own.
#include <array>

#include <Eigen/Geometry>

#include "src/geometry/mesh.hpp"
#include "src/geometry/signed_distance.hpp"
#include "src/grippers/parallel_gripper.hpp"
#include "src/metrics/distance_metrics.hpp"
#include "src/metrics/surface_points.hpp"
#include "src/trial/trial_parameters.hpp"

namespace grip::bench {

class GraspDistances {
 public:
  // `object`: closed and outward, in the object frame. Throws std::invalid_argument for a
  // gripper with soft fingers.
  GraspDistances(const grippers::ParallelGripper& gripper, const geometry::SurfaceMesh& object,
                 const trial::TrialParameters& parameters);

  // fingers: world from finger frame, in grippers::Jaw order; object: world from object frame.
  metrics::DistanceMetrics operator()(const std::array<Eigen::Isometry3d, 2>& fingers,
                                      const Eigen::Isometry3d& object) const;

 private:
  geometry::Vertices finger_;  // one finger, finger frame
  metrics::SurfacePoints points_;
  geometry::SignedDistance object_;
};

}  // namespace grip::bench
