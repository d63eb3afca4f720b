#pragma once
// D1/D2 of a rigid-jaw parallel gripper or a dexterous hand against a rigid object, all at
// given world poses, with the trial's own points and code
// (trial::ParallelTrialScene::grasp_distances, trial::HandTrialScene::grasp_distances): how `grip
// bench peer` measures another engine's settled grasp exactly as grip measures its own.
#include <array>
#include <vector>

#include <Eigen/Geometry>

#include "src/geometry/mesh.hpp"
#include "src/geometry/signed_distance.hpp"
#include "src/grippers/parallel_gripper.hpp"
#include "src/metrics/distance_metrics.hpp"
#include "src/metrics/surface_points.hpp"
#include "src/trial/hand_trial_scene.hpp"
#include "src/trial/trial_parameters.hpp"

namespace grip::bench {

class GraspDistances {
 public:
  // `object`: closed and outward, in the object frame. Soft fingers are measured on their tet
  // mesh's boundary, as the trial samples them.
  GraspDistances(const grippers::ParallelGripper& gripper, const geometry::SurfaceMesh& object,
                 const trial::TrialParameters& parameters);
  // The hand's links with a surface, points sampled on the scene's rest surface as it samples
  // them; `object` as above.
  GraspDistances(const trial::HandTrialScene& hand, const geometry::SurfaceMesh& object,
                 const trial::TrialParameters& parameters);

  // fingers: world from finger frame, in grippers::Jaw order; object: world from object frame.
  // Rigid fingers only.
  metrics::DistanceMetrics operator()(const std::array<Eigen::Isometry3d, 2>& fingers,
                                      const Eigen::Isometry3d& object) const;
  // Soft fingers: each finger's tet vertices in the world, in grippers::Jaw order.
  metrics::DistanceMetrics operator()(const std::array<geometry::Vertices, 2>& fingers,
                                      const Eigen::Isometry3d& object) const;
  // links: world from link frame for every link of the hand's kinematic tree (as
  // KinematicTree::link_poses gives them).
  metrics::DistanceMetrics operator()(const std::vector<Eigen::Isometry3d>& links,
                                      const Eigen::Isometry3d& object) const;

 private:
  metrics::DistanceMetrics at(const std::vector<Eigen::Isometry3d>& part_poses,
                              const Eigen::Isometry3d& object) const;
  // D1/D2 at the gripper's surface vertices in the world, in points_'s order.
  metrics::DistanceMetrics measured(const geometry::Vertices& world,
                                    const Eigen::Isometry3d& object) const;

  std::vector<geometry::Vertices> parts_;  // each part's vertices in its own frame
  Eigen::VectorXi surface_to_tet_;         // soft fingers: surface vertex to tet vertex
  std::vector<int> part_links_;            // the hand's: each part's link
  metrics::SurfacePoints points_;
  geometry::SignedDistance object_;
};

}  // namespace grip::bench
