#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "bench/peer/grasp_distances.hpp"
#include "bench/peer/mujoco_hand_trial.hpp"
#include "bench/peer/mujoco_trial.hpp"
#include "bench/peer/peer_vtk.hpp"
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

// MuJoCo held the object, both jaws at the grip force (within the protocol's tolerance).
void expect_held_at_grip_force(const MujocoOutcome& m, const trial::TrialParameters& p) {
  EXPECT_EQ(m.verdict, "success") << m.message;
  ASSERT_TRUE(m.settled);
  for (const double f : m.closing_forces) {
    EXPECT_NEAR(f, p.grip_force, p.force_tolerance * p.grip_force);
  }
  EXPECT_LT(m.largest_slip, p.displacement_threshold());
}

// grip's trial of one parallel grasp.
trial::TrialOutcome grip_trial(const trial::TrialObject& object,
                               const grippers::ParallelGripper& gripper,
                               const trial::ParallelGrasp& grasp, const trial::TrialParameters& p) {
  const trial::ParallelTrialScene scene(object, gripper, p);
  return trial::run_trials(scene, trial::testing::parallel_candidates({grasp})).front();
}

TEST(PeerBench, CentredBoxIsHeldByBothEngines) {
  const trial::TrialObject object = box();
  const trial::TrialParameters p = parameters();
  const trial::ParallelGrasp grasp = centred(0.035);
  const trial::TrialOutcome grip = grip_trial(object, jaws(), grasp, p);
  EXPECT_EQ(grip.result.record.failure, io::FailureKind::kNone) << grip.failure_reason;

  if (!mujoco_available()) GTEST_SKIP() << "built without MuJoCo: its half is not tested";
  const MujocoOutcome m =
      run_mujoco_trial(object.surface, object.material.density,
                       std::sqrt(object.material.friction * p.rigid_finger_friction), jaws(),
                       grasp.pose, grasp.opening, p);
  expect_held_at_grip_force(m, p);
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
    const synth::SynthesisResult result = synth::synthesize(
        object, grippers::gripper_type(grippers::GripperKind::kLeap), false, params, 1, 1);
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

// The number in `NumberOfPoints="..."` of a VTK file.
long vtk_points(const std::filesystem::path& file) {
  std::ifstream in(file);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t at = text.find("NumberOfPoints=\"");
  return at == std::string::npos ? -1 : std::stol(text.substr(at + 16));
}

// Both engines' VTK series of the box `grasp` (write_peer_jaws_vtk) in the test's folder NAME,
// which it returns.
std::filesystem::path both_engines_vtk(const std::string& name,
                                       const grippers::ParallelGripper& gripper,
                                       const trial::ParallelGrasp& grasp, const MujocoOutcome& m) {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / name;
  std::filesystem::remove_all(dir);
  synth::HandGrasp hand;
  hand.pose = grasp.pose;
  hand.joints = Eigen::VectorXd::Constant(1, grasp.opening);
  write_peer_jaws_vtk(dir, "case", box(), gripper, hand, m, parameters(), 1);
  return dir;
}

TEST(PeerBench, JawsVtkDrawsBothEnginesOverTheSameBodiesEvenUnsettled) {
  if (!mujoco_available()) GTEST_SKIP() << "built without MuJoCo";
  const trial::TrialObject object = box();
  const trial::TrialParameters p = parameters();
  const trial::ParallelGrasp grasp = centred(0.035);
  MujocoSettings settings;
  settings.closing_margin = 0.0;  // the jaws are still moving when closing's time is up
  const MujocoOutcome m = run_mujoco_trial(object.surface, object.material.density, 3.5, jaws(),
                                           grasp.pose, grasp.opening, p, settings);
  ASSERT_EQ(m.verdict, "unsettled") << m.message;
  // Where it ended stands for the settled grasp: the jaws on their paths, the box in place.
  for (const Eigen::Isometry3d& finger : m.fingers) {
    EXPECT_LT((finger.translation() - grasp.pose.translation()).norm(), 0.1);
  }
  EXPECT_LT(m.object.translation().norm(), 0.01);
  const std::filesystem::path dir = both_engines_vtk("peer_jaws_vtk", jaws(), grasp, m);
  const long points = vtk_points(dir / "case_grip_0000.vtu");
  EXPECT_GT(points, 0);
  EXPECT_EQ(vtk_points(dir / "case_mujoco_0000.vtu"), points);
  EXPECT_EQ(vtk_points(dir / "case_mujoco_0001.vtu"), points);
}

// The production fin-ray gripper, as `grip bench peer --gripper fin-ray` simulates it.
const grippers::ParallelGripper& fin_ray() {
  static const grippers::ParallelGripper gripper =
      grippers::make_parallel_gripper(grippers::GripperKind::kFinRay);
  return gripper;
}

// The box centred between the fin-ray's pads, three quarters of the way to their tips.
trial::ParallelGrasp fin_ray_grasp(double opening) {
  const auto z = fin_ray().finger_surface.vertices.col(2);
  trial::ParallelGrasp grasp;
  grasp.pose.translation() =
      Eigen::Vector3d(0.0, 0.0, -(z.minCoeff() + 0.75 * (z.maxCoeff() - z.minCoeff())));
  grasp.opening = opening;
  return grasp;
}

TEST(PeerBench, FinRayGraspOfABoxIsHeldByBothEnginesAndOnlyMujocoPenetrates) {
  const trial::TrialObject object = box();
  const trial::TrialParameters p = parameters();
  const trial::ParallelGrasp grasp = fin_ray_grasp(0.036);
  const trial::TrialOutcome grip = grip_trial(object, fin_ray(), grasp, p);
  EXPECT_EQ(grip.result.record.failure, io::FailureKind::kNone) << grip.failure_reason;
  EXPECT_EQ(grip.result.record.d1, 0.0);

  if (!mujoco_available()) GTEST_SKIP() << "built without MuJoCo: its half is not tested";
  const double mu = fin_ray().soft_finger->material.friction;
  const MujocoOutcome m = run_mujoco_trial(object.surface, object.material.density, mu, fin_ray(),
                                           grasp.pose, grasp.opening, p);
  expect_held_at_grip_force(m, p);
  // MuJoCo's contacts sink in; the fingers' flexes bend without inverting here.
  EXPECT_GT(m.deepest_penetration, 0.0);
  EXPECT_EQ(m.most_inverted_tets, 0);
  const GraspDistances distances(fin_ray(), object.surface, p);
  const metrics::DistanceMetrics d = distances(m.finger_vertices, m.object);
  // Both engines' frames over the same bodies, the flexes' tets with their stress.
  const std::filesystem::path dir = both_engines_vtk("peer_fin_ray_vtk", fin_ray(), grasp, m);
  EXPECT_EQ(vtk_points(dir / "case_mujoco_0000.vtu"), vtk_points(dir / "case_grip_0000.vtu"));
  EXPECT_GT(d.d1, 0.0);
  EXPECT_LT(d.d2, 2e-3);
}

// MuJoCo's flex elements can invert (grip's tets cannot): a finger 1e5 times softer (94 Pa),
// crushed on the box by the 50 N drive, turns some of its tets inside out, and the trial counts
// them.
TEST(PeerBench, MujocoCountsTheTetsItInverts) {
  if (!mujoco_available()) GTEST_SKIP() << "built without MuJoCo";
  grippers::ParallelGripper soft = fin_ray();
  soft.soft_finger->material.youngs_modulus *= 1e-5;
  const trial::TrialObject object = box();
  const trial::ParallelGrasp grasp = fin_ray_grasp(0.036);
  const MujocoOutcome m = run_mujoco_trial(object.surface, object.material.density, 3.5, soft,
                                           grasp.pose, grasp.opening, parameters());
  EXPECT_GT(m.most_inverted_tets, 0) << m.verdict << " " << m.message;
  // The production finger inverts none on the same grasp (the test above).
}

TEST(PeerBench, FinRayDistancesAreTheTrialsAtTheSameVertices) {
  const trial::TrialObject object = box();
  const trial::TrialParameters p = parameters();
  const trial::ParallelTrialScene scene(object, fin_ray(), p);
  const GraspDistances distances(fin_ray(), object.surface, p);
  const geometry::TetMesh& mesh = fin_ray().soft_finger->mesh;
  // Open (D1 = 0) and closed into the box (D1 > 0): the fingers' rest tets placed by the
  // candidate's pose, as the trial places them.
  for (const double opening : {0.036, 0.024}) {
    const trial::ParallelGrasp grasp = fin_ray_grasp(opening);
    solver::Environment environment(scene.model());
    scene.place(environment, grasp);
    const metrics::DistanceMetrics trial = scene.grasp_distances(environment);
    std::array<geometry::Vertices, 2> fingers;
    for (int j = 0; j < 2; ++j) {
      const Eigen::Isometry3d pose =
          grasp.pose * fin_ray().finger_pose(
                           j == 0 ? grippers::Jaw::kPositive : grippers::Jaw::kNegative, opening);
      fingers[j] =
          (mesh.vertices * pose.linear().transpose()).rowwise() + pose.translation().transpose();
    }
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
