#include <gtest/gtest.h>

#include <cmath>

#include "bench/peer/grasp_distances.hpp"
#include "bench/peer/mujoco_trial.hpp"
#include "solver/environment.hpp"
#include "src/geometry/primitives.hpp"
#include "src/grippers/gripper_registry.hpp"
#include "src/trial/grasp_trial.hpp"

namespace grip::bench {
namespace {

const grippers::ParallelGripper& jaws() {
  static const grippers::ParallelGripper gripper =
      grippers::make_parallel_gripper(grippers::GripperKind::kParallelJaw);
  return gripper;
}

// A 4 x 3 x 3 cm box (3 cm across the closing axis) of grip's rigid-object material.
trial::TrialObject box() {
  trial::TrialObject object;
  object.name = "box";
  object.surface = geometry::make_box(Eigen::Vector3d(0.04, 0.03, 0.03));
  object.material.density = 1000.0;
  object.material.friction = 3.5;
  return object;
}

// The box's centre midway along the fingers, the jaws open `opening`.
trial::ParallelGrasp centred(double opening) {
  const auto z = jaws().finger_surface.vertices.col(2);
  trial::ParallelGrasp grasp;
  grasp.pose.translation() = Eigen::Vector3d(0.0, 0.0, -0.5 * (z.minCoeff() + z.maxCoeff()));
  grasp.opening = opening;
  return grasp;
}

trial::TrialParameters parameters() {
  trial::TrialParameters p;
  p.metric_samples = 20000;
  return p;
}

TEST(PeerBench, CentredBoxIsHeldByBothEngines) {
  const trial::TrialObject object = box();
  const trial::TrialParameters p = parameters();
  const trial::ParallelGrasp grasp = centred(0.035);
  const trial::TrialScene scene(object, jaws(), p);
  const trial::TrialOutcome grip = trial::run_trials(scene, {grasp}).front();
  EXPECT_EQ(grip.result.record.failure, io::FailureKind::kNone) << grip.failure_reason;

  if (!mujoco_available()) GTEST_SKIP() << "built without MuJoCo: its half is not tested";
  const MujocoOutcome m =
      run_mujoco_trial(object.surface, object.material.density,
                       std::sqrt(object.material.friction * p.rigid_finger_friction), jaws(),
                       grasp.pose, grasp.opening, p);
  EXPECT_EQ(m.verdict, "success") << m.message;
  ASSERT_TRUE(m.settled);
  for (const double f : m.closing_forces) {
    EXPECT_NEAR(f, p.grip_force, p.force_tolerance * p.grip_force);
  }
  EXPECT_LT(m.largest_slip, p.displacement_threshold());
  // The box stays where the jaws met it, and the jaws touch its faces at y = +-1.5 cm.
  EXPECT_LT(m.object.translation().norm(), 1e-3);
  const GraspDistances distances(jaws(), object.surface, p);
  const metrics::DistanceMetrics d = distances(m.fingers, m.object);
  EXPECT_LT(d.d2, 2e-3);
}

TEST(PeerBench, DistancesAreTheTrialsAtTheSamePoses) {
  const trial::TrialObject object = box();
  const trial::TrialParameters p = parameters();
  const trial::TrialScene scene(object, jaws(), p);
  const GraspDistances distances(jaws(), object.surface, p);
  // Open (D1 = 0) and closed into the box (D1 > 0), turned about the approach axis.
  for (const double opening : {0.036, 0.024}) {
    trial::ParallelGrasp grasp = centred(opening);
    grasp.pose.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    solver::Environment environment(scene.model());
    scene.place(environment, grasp);
    const metrics::DistanceMetrics trial = scene.grasp_distances(environment);
    const std::array<Eigen::Isometry3d, 2> fingers = {
        grasp.pose * jaws().finger_pose(grippers::Jaw::kPositive, opening),
        grasp.pose * jaws().finger_pose(grippers::Jaw::kNegative, opening)};
    const metrics::DistanceMetrics peer = distances(fingers, Eigen::Isometry3d::Identity());
    EXPECT_NEAR(peer.d1, trial.d1, 1e-12) << "opening " << opening;
    EXPECT_NEAR(peer.d2, trial.d2, 1e-12) << "opening " << opening;
    if (opening < 0.03) {
      EXPECT_GT(trial.d1, 1e-3);
    }
  }
}

}  // namespace
}  // namespace grip::bench
