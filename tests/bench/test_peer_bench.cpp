#include <gtest/gtest.h>

#include <cmath>

#include "bench/peer/grasp_distances.hpp"
#include "bench/peer/mujoco_hand_trial.hpp"
#include "bench/peer/mujoco_trial.hpp"
#include "solver/environment.hpp"
#include "src/geometry/primitives.hpp"
#include "src/grippers/coarse_leap_hand.hpp"
#include "src/grippers/gripper_registry.hpp"
#include "src/synth/synthesize.hpp"
#include "src/trial/hand_trial_scene.hpp"
#include "src/trial/parallel_trial_scene.hpp"
#include "src/trial/trial.hpp"
#include "tests/trial/short_trial.hpp"

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
  const trial::ParallelTrialScene scene(object, jaws(), p);
  const trial::TrialOutcome grip =
      trial::run_trials(scene, trial::testing::parallel_candidates({grasp})).front();
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
  const trial::ParallelTrialScene scene(object, jaws(), p);
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

// The LEAP hand as the benchmark simulates it (coarse capsule links).
const grippers::HandModel& leap() {
  static const grippers::HandModel hand = grippers::coarse_leap_hand();
  return hand;
}

// A rigid cylinder of radius 3 cm and length 8 cm along z, 16 sides (the hand trial's test
// object), with the benchmark's friction.
trial::TrialObject cylinder() {
  trial::TrialObject object;
  object.name = "cylinder";
  object.surface = geometry::make_cylinder(0.03, 0.08, 16);
  object.material.density = 500.0;
  object.material.friction = 3.5;
  return object;
}

// A hand candidate synthesized on the cylinder (300 annealing steps, seed 1), the first one:
// index, middle and thumb close on it, and both engines hold it with a slip a fifth of the
// threshold or less.
const trial::HandTrialGrasp& hand_candidate() {
  static const trial::HandTrialGrasp grasp = [] {
    synth::SynthesisParams params;
    params.hand.steps = 300;
    const synth::PreparedObject object(cylinder().surface);
    const synth::SynthesisResult result =
        synth::synthesize(object, grippers::GripperKind::kLeap, false, params, 1, 1);
    const synth::HandGrasp& h = result.candidates.at(0).hands.front();
    return trial::HandTrialGrasp{h.pose, h.joints, h.contacts, h.contact_normals};
  }();
  return grasp;
}

TEST(PeerBench, HandGraspOfACylinderIsHeldByBothEngines) {
  const trial::TrialObject object = cylinder();
  const trial::TrialParameters p = parameters();
  const trial::HandTrialScene scene(object, leap(), "leap", p);
  const trial::HandTrialGrasp& grasp = hand_candidate();
  trial::TrialRunOptions options;
  options.trajectory = false;
  const trial::TrialOutcome grip =
      trial::run_trials(scene, trial::testing::hand_candidates({grasp}), options).front();
  EXPECT_EQ(grip.result.record.failure, io::FailureKind::kNone) << grip.failure_reason;

  if (!mujoco_available()) GTEST_SKIP() << "built without MuJoCo: its half is not tested";
  const MujocoHandOutcome m = run_mujoco_hand_trial(
      object.surface, object.material.density,
      std::sqrt(object.material.friction * p.rigid_finger_friction), scene, grasp, p);
  EXPECT_EQ(m.verdict, "success") << m.message;
  ASSERT_TRUE(m.settled);
  ASSERT_EQ(m.closing_forces.size(), scene.fingers().size());
  // At least two fingers squeeze it, none much harder than the grip force.
  int squeezing = 0;
  for (const double f : m.closing_forces) {
    squeezing += f > 0.0;
    EXPECT_LT(f, 2.0 * p.grip_force);
  }
  EXPECT_GE(squeezing, 2);
  EXPECT_LT(m.largest_slip, p.displacement_threshold());
  EXPECT_EQ(m.links.size(), scene.kinematics().links().size());
  // The palm stays where the candidate put it, and the cylinder within 1 cm of its start.
  EXPECT_LT((m.links.front().translation() - grasp.pose.translation()).norm(), 1e-9);
  EXPECT_LT(m.object.translation().norm(), 1e-2);
  const GraspDistances distances(scene, object.surface, p);
  const metrics::DistanceMetrics d = distances(m.links, m.object);
  EXPECT_LT(d.d1, 1e-3);
  EXPECT_LT(d.d2, 2e-3);
}

TEST(PeerBench, HandDistancesAreTheTrialsAtTheSamePoses) {
  const trial::TrialObject object = cylinder();
  const trial::TrialParameters p = parameters();
  const trial::HandTrialScene scene(object, leap(), "leap", p);
  const GraspDistances distances(scene, object.surface, p);
  // The candidate (D1 = 0) and the hand's root moved to the cylinder's centre (D1 > 0); the
  // object turned and moved so that the object frame is not the world's.
  const Eigen::Isometry3d object_pose =
      Eigen::Translation3d(0.01, -0.02, 0.005) *
      Eigen::AngleAxisd(0.4, Eigen::Vector3d(1.0, 2.0, 3.0).normalized());
  for (const bool inside : {false, true}) {
    trial::HandTrialGrasp grasp = hand_candidate();
    if (inside) grasp.pose.translation().setZero();
    grasp.pose = object_pose * grasp.pose;  // the same relative pose
    const std::vector<Eigen::Isometry3d> links =
        scene.kinematics().link_poses(grasp.pose, grasp.joints);
    // The trial's own measure, object at rest in the world frame, hand relative to it.
    trial::HandTrialGrasp relative = grasp;
    relative.pose = object_pose.inverse() * grasp.pose;
    solver::Environment environment(scene.model());
    scene.place(environment, relative);
    const metrics::DistanceMetrics trial = scene.grasp_distances(environment);
    const metrics::DistanceMetrics peer = distances(links, object_pose);
    EXPECT_NEAR(peer.d1, trial.d1, 1e-12) << "inside " << inside;
    EXPECT_NEAR(peer.d2, trial.d2, 1e-12) << "inside " << inside;
    if (inside) {
      EXPECT_GT(trial.d1, 1e-3);
    }
  }
}

}  // namespace
}  // namespace grip::bench
