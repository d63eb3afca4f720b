// Known outcomes of bimanual grasp trials (two grippers of one kind, the same protocol as one):
// two fin-ray grippers pinching a 36 cm box near its ends close every finger on the grip force
// and hold it, D1 = 0 for both; with frictionless pads the box is squeezed out of both; a right
// and a left LEAP hand synthesized on a large box (grip synth --bimanual) close on it and hold
// it; a batch matches solo runs; a scene of two grippers refuses one-gripper candidates and
// the reverse; and the dataset's gripper record of two grippers describes each one. Small meshes (a
// one-layer fin-ray finger, the coarse hand), so each test runs in seconds.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <stdexcept>
#include <vector>

#include "src/geometry/primitives.hpp"
#include "src/grippers/coarse_leap_hand.hpp"
#include "src/synth/synthesize.hpp"
#include "src/trial/hand_trial_scene.hpp"
#include "src/trial/parallel_trial_scene.hpp"
#include "src/trial/same_result.hpp"
#include "src/trial/trial.hpp"
#include "tests/trial/short_trial.hpp"

namespace grip::trial {
namespace {

using testing::bimanual_candidates;
using testing::bimanual_hand_candidates;
using testing::hand_candidates;
using testing::largest;
using testing::one_layer_fin_ray;
using testing::parallel_candidates;
using testing::short_parameters;

// ---- Two fin-ray grippers ----

// A rigid box 36 cm long (x), 4 cm wide (y) and 3 cm high (z): too long for one gripper to
// hold by its middle under gravity along its length, pinched by two across its width.
TrialObject long_box() {
  TrialObject object;
  object.name = "long box";
  object.surface = geometry::make_box(Eigen::Vector3d(0.36, 0.04, 0.03));
  object.material.density = 500.0;  // 0.22 kg
  return object;
}

// As GraspTrial's centred fin-ray grasp of a 4 cm box: the one-layer finger is far softer than
// the production one, so it squeezes to 10 N and may close 15 mm past the box per jaw.
TrialParameters fin_ray_parameters() {
  TrialParameters p = short_parameters();
  p.squeeze_speed = 0.02;
  p.final_opening = 0.01;
  p.grip_force = 10.0;
  return p;
}

// Both grippers approach from below (-z), closing across the box's width (y), 12 cm either side
// of its centre, jaws open 2.3 mm beyond the width.
std::array<ParallelGrasp, 2> pinched_near_the_ends() {
  std::array<ParallelGrasp, 2> grasps;
  for (int g = 0; g < 2; ++g) {
    grasps[g].pose.translation() = Eigen::Vector3d(g == 0 ? -0.12 : 0.12, 0.0, -0.05);
    grasps[g].opening = 0.04 + 0.0046;
  }
  return grasps;
}

TEST(BimanualTrial, TwoFinRayGrippersHoldALongBoxWithFrictionAndSqueezeItOutWithout) {
  const TrialParameters p = fin_ray_parameters();
  const ParallelTrialScene scene(long_box(), one_layer_fin_ray(), p, 2);
  ASSERT_EQ(scene.gripper_count(), 2);
  ASSERT_EQ(scene.jaws().size(), 4u);
  const TrialOutcome held =
      run_trials(scene, bimanual_candidates({pinched_near_the_ends()})).front();
  const io::CandidateRecord& h = held.result.record;
  EXPECT_EQ(h.failure, io::FailureKind::kNone)
      << io::to_string(h.failure) << " " << held.failure_reason;
  EXPECT_LT(largest(h.displacement), p.displacement_threshold());
  // All four fingers (the first gripper's two, then the second's) touch and stop on force.
  EXPECT_TRUE(held.closed);
  ASSERT_EQ(h.closing_forces.size(), 4u);
  for (double f : h.closing_forces) EXPECT_NEAR(f, p.grip_force, p.force_tolerance * p.grip_force);
  EXPECT_EQ(h.d1, 0.0);  // IPC never penetrates
  EXPECT_GT(h.d2, 0.0);
  EXPECT_LT(h.d2, p.sim.d_hat);
  ASSERT_EQ(held.gripper_distances.size(), 2u);
  for (const metrics::DistanceMetrics& d : held.gripper_distances) {
    EXPECT_EQ(d.d1, 0.0);
    EXPECT_LT(d.d2, p.sim.d_hat);
  }
  EXPECT_EQ(h.contact_friction, 3.5);
  // The record and frames carry both grippers: two poses, two openings.
  EXPECT_EQ(h.hand_poses.size(), 24u);
  EXPECT_EQ(h.hand_poses[3], -0.12);
  EXPECT_EQ(h.hand_poses[12 + 3], 0.12);
  EXPECT_EQ(h.joints.size(), 2u);
  const io::TrajectoryRecord& t = *held.result.trajectory;
  const std::size_t frames = static_cast<std::size_t>(p.closing_frames + p.validation_frames);
  EXPECT_EQ(t.hand_poses.size(), frames * 24);
  EXPECT_EQ(t.joints.size(), frames * 2);
  EXPECT_EQ(t.gripper_vertices.size(),
            frames * 3 * static_cast<std::size_t>(scene.gripper_surface_vertex_count()));

  // Frictionless pads (mu = 0): the same squeeze to the grip force, but, as with one gripper,
  // the wrapping fingers' converging normals push the released box out along their approach
  // axis (+z, the same for both grippers) before any gravity phase: it leaves every finger.
  grippers::ParallelGripper slick = one_layer_fin_ray();
  slick.soft_finger->material.friction = 0.0;
  const ParallelTrialScene slick_scene(long_box(), slick, p, 2);
  const TrialOutcome lost =
      run_trials(slick_scene, bimanual_candidates({pinched_near_the_ends()})).front();
  const io::CandidateRecord& r = lost.result.record;
  EXPECT_EQ(r.failure, io::FailureKind::kNoContact)
      << io::to_string(r.failure) << " " << lost.failure_reason;
  EXPECT_TRUE(lost.closed);
  ASSERT_EQ(r.closing_forces.size(), 4u);
  for (double f : r.closing_forces) EXPECT_NEAR(f, p.grip_force, p.force_tolerance * p.grip_force);
  EXPECT_EQ(r.d1, 0.0);
}

TEST(BimanualTrial, AScenesGripperCountMustMatchItsCandidates) {
  const TrialParameters p = fin_ray_parameters();
  const ParallelTrialScene one(long_box(), one_layer_fin_ray(), p);
  const ParallelTrialScene two(long_box(), one_layer_fin_ray(), p, 2);
  EXPECT_THROW(run_trials(one, bimanual_candidates({pinched_near_the_ends()})),
               std::invalid_argument);
  EXPECT_THROW(run_trials(two, parallel_candidates({pinched_near_the_ends()[0]})),
               std::invalid_argument);
  EXPECT_THROW(ParallelTrialScene(long_box(), one_layer_fin_ray(), p, 3), std::invalid_argument);
  // The second gripper's bodies follow the first's, named apart.
  const auto& bodies = two.model()->scene().bodies;
  EXPECT_EQ(bodies.size(), 1u + 2u * 2u * 2u);  // the object, then per jaw a jaw and a finger
  EXPECT_EQ(bodies[static_cast<std::size_t>(two.jaws()[1].finger)].name, "finger-");
  EXPECT_EQ(bodies[static_cast<std::size_t>(two.jaws()[3].finger)].name, "finger- 2");
}

TEST(BimanualTrial, BatchMatchesSoloRunsForAnyThreadCount) {
  // Rigid jaws (kinematic fingers, a fast trial): the grasp near the ends, one nearer the centre,
  // and one whose second gripper's jaws start inside the box (it leaves the batch at once).
  const grippers::ParallelGripper jaws = grippers::make_rigid_jaw_gripper();
  const ParallelTrialScene scene(long_box(), jaws, short_parameters(), 2);
  std::vector<std::array<ParallelGrasp, 2>> grasps(3, pinched_near_the_ends());
  grasps[1][0].pose.translation().x() = -0.05;
  grasps[1][1].pose.translation().x() = 0.05;
  grasps[2][1].opening = 0.03;  // the box is 4 cm wide
  TrialRunOptions batch_options;
  batch_options.threads = 2;
  const std::vector<TrialOutcome> batch =
      run_trials(scene, bimanual_candidates(grasps), batch_options);
  ASSERT_EQ(batch.size(), grasps.size());
  for (std::size_t k = 0; k < grasps.size(); ++k) {
    TrialRunOptions solo_options;
    solo_options.threads = 1;
    solo_options.ids = {k};
    const TrialOutcome solo =
        run_trials(scene, bimanual_candidates({grasps[k]}), solo_options).front();
    EXPECT_TRUE(same_result(batch[k].result, solo.result)) << "candidate " << k;
  }
  EXPECT_EQ(batch[0].result.record.failure, io::FailureKind::kNone) << batch[0].failure_reason;
  EXPECT_EQ(batch[2].result.record.failure, io::FailureKind::kInitialPenetration);
}

// ---- A right and a left hand ----

const grippers::HandModel& coarse_hand(grippers::HandSide side) {
  static const grippers::HandModel right = grippers::coarse_leap_hand(grippers::HandSide::kRight);
  static const grippers::HandModel left = grippers::coarse_leap_hand(grippers::HandSide::kLeft);
  return side == grippers::HandSide::kRight ? right : left;
}

// A rigid box of 30 x 15 x 15 cm, 0.34 kg: larger than one hand spans.
TrialObject large_box() {
  TrialObject object;
  object.name = "large box";
  object.surface = geometry::make_box(Eigen::Vector3d(0.30, 0.15, 0.15));
  object.material.density = 100.0;
  object.material.friction = 1.0;
  return object;
}

// A bimanual candidate synthesized on the large box as grip synth --bimanual makes it (a right
// and a left pool of unimanual candidates, 300 annealing steps each, composed), seed 1.
const std::array<HandTrialGrasp, 2>& synthesized_pair() {
  static const std::array<HandTrialGrasp, 2> pair = [] {
    synth::SynthesisParams params;
    params.hand.steps = 300;
    const synth::PreparedObject object(large_box().surface);
    const synth::SynthesisResult result = synth::synthesize(
        object, grippers::gripper_type(grippers::GripperKind::kLeap), true, params, 1, 1);
    const synth::Candidate& c = result.candidates.at(0);
    std::array<HandTrialGrasp, 2> grasps;
    for (std::size_t h = 0; h < 2; ++h) {
      const synth::HandGrasp& g = c.hands.at(h);
      grasps[h] = HandTrialGrasp{g.pose, g.joints, g.contacts, g.contact_normals};
    }
    return grasps;
  }();
  return pair;
}

TEST(BimanualTrial, ARightAndALeftHandHoldALargeBox) {
  const TrialParameters p = short_parameters();
  std::vector<grippers::HandModel> hands = {coarse_hand(grippers::HandSide::kRight),
                                            coarse_hand(grippers::HandSide::kLeft)};
  const HandTrialScene scene(large_box(), std::move(hands), "leap", p);
  ASSERT_EQ(scene.hand_count(), 2);
  ASSERT_EQ(scene.fingers().size(), 8u);
  EXPECT_EQ(scene.fingers()[4].name, "index 2");
  EXPECT_EQ(scene.fingers()[4].hand, 1);
  const TrialOutcome outcome =
      run_trials(scene, bimanual_hand_candidates({synthesized_pair()})).front();
  const io::CandidateRecord& r = outcome.result.record;
  EXPECT_EQ(r.failure, io::FailureKind::kNone)
      << io::to_string(r.failure) << " " << outcome.failure_reason;
  EXPECT_LT(largest(r.displacement), p.displacement_threshold());
  // Every finger of both hands that touches pushes with the grip force, and each hand touches
  // with at least two.
  EXPECT_TRUE(outcome.closed);
  ASSERT_EQ(r.closing_forces.size(), 8u);
  for (int h = 0; h < 2; ++h) {
    int touching = 0;
    for (int f = 4 * h; f < 4 * h + 4; ++f) {
      const double force = r.closing_forces[static_cast<std::size_t>(f)];
      if (force <= 0.0) continue;
      ++touching;
      EXPECT_NEAR(force, p.grip_force, p.force_tolerance * p.grip_force) << "finger " << f;
    }
    EXPECT_GE(touching, 2) << "hand " << h;
  }
  EXPECT_EQ(r.d1, 0.0);
  ASSERT_EQ(outcome.gripper_distances.size(), 2u);
  for (const metrics::DistanceMetrics& d : outcome.gripper_distances) EXPECT_EQ(d.d1, 0.0);
  // Both hands' poses and joints, the right hand's first.
  EXPECT_EQ(r.hand_poses.size(), 24u);
  EXPECT_EQ(r.hand_poses[3], synthesized_pair()[0].pose.translation().x());
  EXPECT_EQ(r.hand_poses[12 + 3], synthesized_pair()[1].pose.translation().x());
  ASSERT_EQ(r.joints.size(), 32u);
  EXPECT_EQ(r.joints[16], synthesized_pair()[1].joints[0]);
}

TEST(BimanualTrial, AHandScenesCountMustMatchItsCandidates) {
  const HandTrialScene one(large_box(), coarse_hand(grippers::HandSide::kRight), "leap",
                           short_parameters());
  HandTrialGrasp open;  // a hand 30 cm above the box, joints at 0
  open.pose.translation() = Eigen::Vector3d(0.0, 0.0, 0.3);
  open.joints = Eigen::VectorXd::Zero(16);
  EXPECT_THROW(run_trials(one, bimanual_hand_candidates({{open, open}})), std::invalid_argument);
  std::vector<grippers::HandModel> hands = {coarse_hand(grippers::HandSide::kRight),
                                            coarse_hand(grippers::HandSide::kLeft)};
  const HandTrialScene two(large_box(), std::move(hands), "leap", short_parameters());
  EXPECT_THROW(run_trials(two, hand_candidates({open})), std::invalid_argument);
  EXPECT_EQ(two.hand_count(), 2);
  EXPECT_THROW(
      HandTrialScene(large_box(), std::vector<grippers::HandModel>{}, "leap", short_parameters()),
      std::invalid_argument);
}

// The dataset's record of two grippers: hands = 2, its own name, joint and finger names per
// hand, and both hands' surfaces, each in its own frame, in the order of the frames' vertices.
TEST(BimanualTrial, GripperRecordDescribesBothGrippers) {
  std::vector<grippers::HandModel> hands = {coarse_hand(grippers::HandSide::kRight),
                                            coarse_hand(grippers::HandSide::kLeft)};
  const HandTrialScene two(large_box(), std::move(hands), "leap", short_parameters());
  const HandTrialScene one(large_box(), coarse_hand(grippers::HandSide::kRight), "leap",
                           short_parameters());
  const io::GripperRecord r2 = two.gripper_record(), r1 = one.gripper_record();
  EXPECT_EQ(r1.hands, 1u);
  EXPECT_EQ(r2.hands, 2u);
  EXPECT_EQ(r1.name, "leap");
  EXPECT_EQ(r2.name, "leap-bimanual");
  EXPECT_EQ(r2.joint_names, r1.joint_names);
  EXPECT_EQ(r2.joint_names.size(), 16u);
  EXPECT_EQ(r2.finger_names, r1.finger_names);
  EXPECT_EQ(r2.finger_names.size(), 4u);
  // The right hand's surface as one hand's record has it, then the left hand's (its mirror
  // through the x-z plane: the same extent in x and z, the other side in y).
  const std::size_t n = r1.vertex_count();
  ASSERT_EQ(r2.vertex_count(), 2 * n);
  EXPECT_EQ(std::vector<double>(r2.vertices.begin(), r2.vertices.begin() + 3 * n), r1.vertices);
  ASSERT_EQ(r2.triangles.size(), 2 * r1.triangles.size());
  EXPECT_EQ(
      std::vector<std::int32_t>(r2.triangles.begin(), r2.triangles.begin() + r1.triangles.size()),
      r1.triangles);
  const geometry::Vertices left =
      Eigen::Map<const geometry::Vertices>(r2.vertices.data() + 3 * n, n, 3);
  const geometry::Vertices right = Eigen::Map<const geometry::Vertices>(r2.vertices.data(), n, 3);
  EXPECT_NEAR(left.col(1).minCoeff(), -right.col(1).maxCoeff(), 0.02);
  EXPECT_NEAR(left.col(2).maxCoeff(), right.col(2).maxCoeff(), 1e-9);
  for (std::size_t i = r1.triangles.size(); i < r2.triangles.size(); ++i) {
    EXPECT_GE(r2.triangles[i], static_cast<std::int32_t>(n));
    EXPECT_LT(r2.triangles[i], static_cast<std::int32_t>(2 * n));
  }
  // The frames' order: surface_vertices at rest is the record's surface.
  EXPECT_EQ(two.rest_surface().vertices.rows(), static_cast<Eigen::Index>(2 * n));

  const ParallelTrialScene jaws(
      long_box(), grippers::make_parallel_gripper(grippers::GripperKind::kParallelJaw),
      short_parameters(), 2);
  const io::GripperRecord parallel = jaws.gripper_record();
  EXPECT_EQ(parallel.hands, 2u);
  EXPECT_EQ(parallel.name.substr(parallel.name.size() - 9), "-bimanual");
  EXPECT_EQ(parallel.joint_names, std::vector<std::string>{"opening"});
  EXPECT_EQ(parallel.finger_names.size(), 2u);
  EXPECT_EQ(jaws.gripper_surface_vertex_count(), static_cast<int>(parallel.vertex_count()));
}

}  // namespace
}  // namespace grip::trial
