// Known outcomes of the grasp trial with the LEAP-style hand (GRIP, Sec. III-D): a hand
// synthesized on a coarse rigid cylinder closes on it (held) until every touching finger pushes
// with 50 N within 5 %, the released cylinder settles within 1 mm of where it was, no link ever
// intersects the object, D1 = 0, the record and trajectory follow the dataset's layout and the
// hand's gripper record, a hand closing on air finds no contact, and a batch matches solo runs.
// The hand is the shipped one with coarser capsules (8 sides).
#include "src/trial/hand_trial_scene.hpp"
#include "src/trial/trial.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "src/geometry/intersections.hpp"
#include "src/geometry/primitives.hpp"
#include "src/grippers/coarse_leap_hand.hpp"
#include "src/synth/synthesize.hpp"
#include "src/trial/same_result.hpp"
#include "tests/trial/short_trial.hpp"

namespace grip::trial {
namespace {

using testing::hand_candidates;
using testing::short_parameters;

const grippers::HandModel& leap() {
  static const grippers::HandModel hand = grippers::coarse_leap_hand();
  return hand;
}

// A rigid cylinder of radius 3 cm and length 8 cm along z, 16 sides.
TrialObject cylinder() {
  TrialObject object;
  object.name = "cylinder";
  object.surface = geometry::make_cylinder(0.03, 0.08, 16);
  object.material.density = 500.0;
  object.material.friction = 1.0;
  return object;
}

// A hand candidate synthesized on the cylinder (300 annealing steps, seed 1) whose fingers all
// close on it: the second one.
const HandTrialGrasp& closing_candidate() {
  static const HandTrialGrasp grasp = [] {
    synth::SynthesisParams params;
    params.hand.steps = 300;
    const synth::PreparedObject object(cylinder().surface);
    const synth::SynthesisResult result = synth::synthesize(
        object, grippers::gripper_type(grippers::GripperKind::kLeap), false, params, 1, 2);
    const synth::HandGrasp& h = result.candidates.at(1).hands.front();
    return HandTrialGrasp{h.pose, h.joints, h.contacts, h.contact_normals};
  }();
  return grasp;
}

// The hand far above the cylinder, palm down, joints at 0: every finger closes on air.
HandTrialGrasp on_air() {
  HandTrialGrasp grasp;
  grasp.pose.translation() = Eigen::Vector3d(0.0, 0.0, 0.3);
  grasp.joints = Eigen::VectorXd::Zero(16);
  return grasp;
}

// Exact intersections between the object (body 0) and the hand's links in one recorded frame.
int object_hand_intersections(const solver::Model& model, const BodyFrame& frame) {
  const auto& bodies = model.scene().bodies;
  geometry::Vertices positions(0, 3);
  std::vector<Eigen::Vector3i> faces;
  std::set<std::pair<int, int>> edges;
  std::vector<int> vertex_body;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const auto offset = static_cast<int>(positions.rows());
    geometry::Vertices next(offset + frame.vertices[b].rows(), 3);
    next << positions, frame.vertices[b];
    positions = std::move(next);
    vertex_body.insert(vertex_body.end(), frame.vertices[b].rows(), static_cast<int>(b));
    for (Eigen::Index f = 0; f < bodies[b].triangles.rows(); ++f) {
      const Eigen::Vector3i t = bodies[b].triangles.row(f).transpose().array() + offset;
      faces.push_back(t);
      for (int k = 0; k < 3; ++k)
        edges.emplace(std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3]));
    }
  }
  geometry::Triangles face_rows(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    face_rows.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
  geometry::Edges edge_rows(static_cast<Eigen::Index>(edges.size()), 2);
  Eigen::Index e = 0;
  for (const auto& [a, b] : edges) edge_rows.row(e++) << a, b;
  return geometry::count_intersections(positions, face_rows, edge_rows, vertex_body,
                                       [](int a, int b) { return a != b && (a == 0 || b == 0); });
}

TEST(HandTrial, SynthesizedGraspClosesOnACylinderWithoutIntersecting) {
  // Every step is recorded: closing frames for more states than closing and settling take, and
  // one validation frame per gravity step.
  TrialParameters p = short_parameters();
  p.closing_frames = 600;
  p.validation_frames = 30;
  const HandTrialScene scene(cylinder(), leap(), "leap", p);
  TrialRunOptions options;
  options.body_frames = true;
  const HandTrialGrasp& grasp = closing_candidate();
  const TrialOutcome outcome = run_trials(scene, hand_candidates({grasp}), options).front();
  const io::CandidateRecord& r = outcome.result.record;
  SCOPED_TRACE(std::string(io::to_string(r.failure)) + " " + outcome.failure_reason);
  EXPECT_NE(r.failure, io::FailureKind::kInitialPenetration);
  EXPECT_NE(r.failure, io::FailureKind::kNewtonLimit);
  EXPECT_NE(r.failure, io::FailureKind::kNumerical);
  EXPECT_NE(r.failure, io::FailureKind::kNoContact);
  // Closing on the held cylinder ends with every touching finger at the grip force, at least
  // two of them touching; released, the cylinder settles less than 1 mm from where it was.
  EXPECT_TRUE(outcome.closed);
  ASSERT_EQ(r.closing_forces.size(), 4u);
  const double tolerance = p.force_tolerance * p.grip_force;
  int touching = 0;
  for (const double force : r.closing_forces) {
    if (force <= 0.0) continue;
    ++touching;
    EXPECT_NEAR(force, p.grip_force, tolerance);
  }
  EXPECT_GE(touching, 2);
  EXPECT_LT(outcome.settle_displacement, 1e-3);
  // And the grasp holds through the six gravity phases.
  EXPECT_EQ(r.failure, io::FailureKind::kNone);
  {
    EXPECT_EQ(r.d1, 0.0);  // IPC never penetrates
    // Held within the barrier's reach (the D1/D2 points sample the capsules' surfaces, so the
    // nearest of them may sit a little farther than the contact itself).
    EXPECT_GT(r.d2, 0.0);
    EXPECT_LT(r.d2, 2.0 * p.sim.d_hat);
    // The verdict follows the displacements and the phases' times.
    EXPECT_EQ(r.status == io::Status::kSuccess,
              !slipped_beyond_threshold(p, r.displacement, r.phase_seconds));
  }
  EXPECT_EQ(r.joints, std::vector<double>(grasp.joints.data(), grasp.joints.data() + 16));

  // The trajectory in the dataset's layout, the hand's vertices in the gripper record's order.
  ASSERT_TRUE(outcome.result.trajectory.has_value());
  const io::TrajectoryRecord& t = *outcome.result.trajectory;
  const std::size_t frames = 600 + 30;
  EXPECT_EQ(t.gripper_vertices.size(), frames * scene.gripper_record().vertex_count() * 3);
  EXPECT_EQ(t.gripper_contact_forces.size(), t.gripper_vertices.size());
  EXPECT_EQ(t.gripper_friction_forces.size(), t.gripper_vertices.size());
  EXPECT_EQ(t.joints.size(), frames * 16);
  EXPECT_EQ(t.hand_poses.size(), frames * 12);
  // The first frame is the placed hand: each finger at or beyond the candidate's joints along
  // its closing path, so no joint moved against that path's direction.
  const Eigen::VectorXd q0 = Eigen::Map<const Eigen::VectorXd>(t.joints.data(), 16);
  for (int f = 0; f < 4; ++f) {
    const Eigen::VectorXd direction = scene.closing_direction(grasp, f);
    for (int dof : scene.fingers()[static_cast<std::size_t>(f)].dofs) {
      EXPECT_GE(direction[dof] * (q0[dof] - grasp.joints[dof]), -1e-12) << "joint " << dof;
    }
  }

  // Every accepted step is among the frames, and none has an object-link intersection.
  std::set<long> steps;
  for (const BodyFrame& frame : outcome.body_frames) {
    steps.insert(std::lround(frame.time / p.sim.dt));
    EXPECT_EQ(object_hand_intersections(*scene.model(), frame), 0) << "t = " << frame.time;
  }
  EXPECT_EQ(steps.size(), r.newton.steps + 1);
}

TEST(HandTrial, ClosingOnAirFindsNoContact) {
  TrialParameters p = short_parameters();
  const HandTrialScene scene(cylinder(), leap(), "leap", p);
  const HandTrialGrasp air = on_air();
  const TrialOutcome outcome = run_trials(scene, hand_candidates({air})).front();
  const io::CandidateRecord& r = outcome.result.record;
  EXPECT_EQ(r.failure, io::FailureKind::kNoContact) << outcome.failure_reason;
  EXPECT_EQ(r.closing_forces, std::vector<double>(4, 0.0));
  EXPECT_EQ(outcome.closing_at_path_end, std::vector<bool>(4, true));
  // Nothing lies on any finger's closing path, so placement put every finger at the end of its
  // path before the first step: in the first frame one of each finger's joints is at a limit
  // and every finger flexed, and the closing never moved them on.
  const io::TrajectoryRecord& t = *outcome.result.trajectory;
  const grippers::KinematicTree& tree = scene.kinematics();
  const std::size_t last = 16 * (scene.parameters().closing_frames - 1);
  for (const HandFinger& finger : scene.fingers()) {
    double nearest = std::numeric_limits<double>::infinity();
    for (int dof : finger.dofs) {
      const double q = t.joints[dof];
      nearest = std::min({nearest, q - tree.lower_limits()[dof], tree.upper_limits()[dof] - q});
      EXPECT_EQ(t.joints[last + dof], q) << finger.name;
    }
    EXPECT_LT(nearest, 1e-9) << finger.name;
    EXPECT_GT(t.joints[finger.dofs[1]], 0.5) << finger.name;  // its second joint flexed
  }
}

TEST(HandTrial, StartingInsideTheObjectIsAnInitialPenetration) {
  const HandTrialScene scene(cylinder(), leap(), "leap", short_parameters());
  HandTrialGrasp inside = on_air();
  inside.pose.translation() = Eigen::Vector3d(-0.05, 0.0, 0.01);  // the palm through the cylinder
  const TrialOutcome outcome = run_trials(scene, hand_candidates({inside})).front();
  EXPECT_EQ(outcome.result.record.failure, io::FailureKind::kInitialPenetration);
  EXPECT_EQ(outcome.result.record.newton.steps, 0u);
}

TEST(HandTrial, BatchMatchesSoloRuns) {
  const HandTrialScene scene(cylinder(), leap(), "leap", short_parameters());
  // A grasp that closes and one that starts inside the cylinder (and leaves the batch at once).
  std::vector<HandTrialGrasp> grasps = {closing_candidate(), on_air()};
  grasps.back().pose.translation() = Eigen::Vector3d(-0.05, 0.0, 0.01);
  TrialRunOptions batch_options;
  batch_options.threads = 2;
  const std::vector<TrialOutcome> batch = run_trials(scene, hand_candidates(grasps), batch_options);
  ASSERT_EQ(batch.size(), grasps.size());
  for (std::size_t k = 0; k < grasps.size(); ++k) {
    TrialRunOptions solo_options;
    solo_options.threads = 1;
    solo_options.ids = {k};
    const TrialOutcome solo = run_trials(scene, hand_candidates({grasps[k]}), solo_options).front();
    EXPECT_TRUE(same_result(batch[k].result, solo.result)) << "candidate " << k;
  }
  EXPECT_EQ(batch.back().result.record.failure, io::FailureKind::kInitialPenetration);
}

TEST(HandTrial, RejectsJointsTheHandCannotTake) {
  const HandTrialScene scene(cylinder(), leap(), "leap", short_parameters());
  HandTrialGrasp bent = on_air();
  bent.joints[1] = 3.0;  // index MCP beyond its 2.23 rad limit
  EXPECT_THROW(run_trials(scene, hand_candidates({bent})), std::out_of_range);
  bent.joints.resize(15);
  EXPECT_THROW(run_trials(scene, hand_candidates({bent})), std::out_of_range);
}

TEST(HandTrial, GripperRecordDescribesTheHand) {
  const HandTrialScene scene(cylinder(), leap(), "leap", short_parameters());
  const io::GripperRecord r = scene.gripper_record();
  EXPECT_EQ(r.name, "leap");
  EXPECT_EQ(r.kind, "hand");
  EXPECT_EQ(r.hands, 1u);
  ASSERT_EQ(r.joint_names.size(), 16u);
  EXPECT_EQ(r.joint_names.front(), "index_abd");
  EXPECT_EQ(r.joint_names.back(), "thumb_ip");
  EXPECT_EQ(r.finger_names, (std::vector<std::string>{"index", "middle", "ring", "thumb"}));
  EXPECT_EQ(r.vertex_count(), static_cast<std::size_t>(scene.rest_surface().vertices.rows()));
  EXPECT_EQ(r.triangles.size(),
            3 * static_cast<std::size_t>(scene.rest_surface().triangles.rows()));
  // Each finger has four links and four joints.
  for (const HandFinger& finger : scene.fingers()) {
    EXPECT_EQ(finger.bodies.size(), 4u) << finger.name;
    EXPECT_EQ(finger.dofs.size(), 4u) << finger.name;
  }
}

}  // namespace
}  // namespace grip::trial
