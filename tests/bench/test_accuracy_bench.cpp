// The work-precision benchmark's measures (bench/accuracy/): a run against itself has no
// error, a known offset of the object's pose, its vertices or its slip gives that error, the
// verdict follows the reference's threshold, the Pareto front of a hand-made table, and one
// sweep point of a standard scene run end to end.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "bench/accuracy/accuracy_scenes.hpp"
#include "bench/accuracy/pareto_front.hpp"
#include "bench/accuracy/trial_error.hpp"

namespace grip::bench {
namespace {

constexpr int kFrames = 3;

// A held candidate with three frames: the gripper turned 0.5 rad about z and moved, the object
// at rest at the origin, two object and one gripper vertex.
io::CandidateResult candidate() {
  io::CandidateResult result;
  result.record.status = io::Status::kSuccess;
  result.record.displacement = {1e-4, 1e-4, 2e-4, 1e-4, 3e-4, 1e-4};
  result.record.phase_seconds = {0.1, 0.1, 0.1, 0.1, 0.1, 0.1};
  io::TrajectoryRecord t;
  Eigen::Isometry3d gripper = Eigen::Isometry3d::Identity();
  gripper.rotate(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()));
  gripper.pretranslate(Eigen::Vector3d(0.01, -0.02, 0.05));
  for (int f = 0; f < kFrames; ++f) {
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) {
        t.hand_poses.push_back(gripper.matrix()(r, c));
        t.object_poses.push_back(r == c ? 1.0 : 0.0);
      }
    }
    t.object_vertices.insert(t.object_vertices.end(), {0.01f, 0.0f, 0.0f, -0.01f, 0.0f, 0.0f});
    t.gripper_vertices.insert(t.gripper_vertices.end(), {0.0f, 0.02f, 0.0f});
  }
  result.trajectory = t;
  return result;
}

// The protocol's defaults with a verdict threshold of `metres` before the creep allowance (eps_v,
// 1 mm/s, times the time under gravity).
trial::TrialParameters judged_by(double metres) {
  trial::TrialParameters p;
  p.displacement_factor = metres / (p.sim.eps_v * p.sim.dt);
  return p;
}

// Moves the object of frame `frame` by `offset` and turns it by `angle` about x.
void move_object(io::CandidateResult& result, int frame, const Eigen::Vector3d& offset,
                 double angle) {
  const Eigen::Matrix3d r = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitX()).matrix();
  std::vector<double>& poses = result.trajectory->object_poses;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) poses[12 * frame + 4 * i + j] = r(i, j);
    poses[12 * frame + 4 * i + 3] += offset[i];
  }
}

TEST(AccuracyBench, ARunAgainstItselfHasNoError) {
  const io::CandidateResult a = candidate();
  const TrialError e = trial_error(a, a, kFrames, judged_by(1e-3));
  EXPECT_EQ(e.translation, 0.0);
  EXPECT_EQ(e.rotation, 0.0);
  EXPECT_EQ(e.slip, 0.0);
  EXPECT_EQ(e.vertices, 0.0);
  EXPECT_TRUE(e.verdict_agrees);
}

TEST(AccuracyBench, AKnownPoseOffsetGivesTheKnownError) {
  const io::CandidateResult reference = candidate();
  io::CandidateResult run = candidate();
  move_object(run, 1, Eigen::Vector3d(0.003, 0.0, -0.004), 0.2);  // 5 mm, 0.2 rad
  move_object(run, 2, Eigen::Vector3d(0.001, 0.0, 0.0), 0.0);
  run.trajectory->gripper_vertices[3 * 2 + 1] += 0.007f;  // the last frame's gripper vertex
  const TrialError e = trial_error(run, reference, kFrames, judged_by(1e-3));
  EXPECT_NEAR(e.translation, 0.005, 1e-12);  // the gripper's turn leaves the distance alone
  EXPECT_NEAR(e.rotation, 0.2, 1e-12);
  EXPECT_NEAR(e.vertices, 0.007, 1e-6);  // floats
  EXPECT_EQ(e.slip, 0.0);
  EXPECT_TRUE(e.verdict_agrees);
  // Only the compared frames count: an offset in a frame before them is no error.
  io::CandidateResult earlier = candidate();
  move_object(earlier, 0, Eigen::Vector3d(0.01, 0.0, 0.0), 0.0);
  EXPECT_EQ(trial_error(earlier, reference, kFrames - 1, judged_by(1e-3)).translation, 0.0);
}

TEST(AccuracyBench, SlipAndVerdictFollowTheReferenceThreshold) {
  const io::CandidateResult reference = candidate();
  io::CandidateResult run = candidate();
  run.record.displacement[4] = 2.3e-3;  // the +z phase slips past 1 mm
  run.record.status = io::Status::kFailure;
  run.record.failure = io::FailureKind::kDisplaced;
  TrialError e = trial_error(run, reference, kFrames, judged_by(1e-3));
  EXPECT_NEAR(e.slip, 2.0e-3, 1e-12);
  EXPECT_FALSE(e.verdict_agrees);
  // Judged by a 3 mm bar (a run whose own dt or eps_v raised it), both hold.
  EXPECT_TRUE(held(run.record, judged_by(3e-3)));
  EXPECT_TRUE(trial_error(run, reference, kFrames, judged_by(3e-3)).verdict_agrees);
  // The threshold grows by eps_v times the time under gravity (0.5 s by the +z phase's end): a
  // slip of 1.4 mm there is held by a 1 mm bar; had the phases waited 0.2 s each for the object
  // to come to rest (1 s under gravity by then), 1.9 mm would be.
  run.record.displacement[4] = 1.4e-3;
  EXPECT_TRUE(held(run.record, judged_by(1e-3)));
  run.record.displacement[4] = 1.9e-3;
  EXPECT_FALSE(held(run.record, judged_by(1e-3)));
  run.record.phase_seconds.fill(0.2);
  EXPECT_TRUE(held(run.record, judged_by(1e-3)));
  // A run that never reached the gravity phases slips by the reference's whole displacement.
  run.record.displacement.fill(std::numeric_limits<double>::quiet_NaN());
  run.record.failure = io::FailureKind::kNoContact;
  e = trial_error(run, reference, kFrames, judged_by(1e-3));
  EXPECT_NEAR(e.slip, 3e-4, 1e-12);
  EXPECT_FALSE(e.verdict_agrees);
}

TEST(AccuracyBench, RunErrorAveragesCandidatesAndCountsVerdicts) {
  trial::TrialOutcome a, b;
  a.result = candidate();
  b.result = candidate();
  move_object(b.result, 2, Eigen::Vector3d(0.004, 0.0, 0.0), 0.0);
  b.result.record.failure = io::FailureKind::kLostContact;
  const RunError e = run_error({a, b}, {a, a}, kFrames, judged_by(1e-3));
  EXPECT_EQ(e.candidates, 2);
  EXPECT_EQ(e.agreeing, 1);
  EXPECT_NEAR(e.translation, 0.002, 1e-12);
  EXPECT_THROW(run_error({a}, {a, a}, kFrames, judged_by(1e-3)), std::invalid_argument);
}

TEST(AccuracyBench, ParetoFrontOfAHandMadeTable) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // (wall time, error): 0 and 2 trade cost for error, 1 is beaten by 0 on both, 3 ties 2's
  // cost with more error, 4 is cheapest and exact-equal to nothing, 5 has no error measured.
  const std::vector<CostError> table = {{1.0, 0.010}, {1.5, 0.020}, {4.0, 0.001},
                                        {4.0, 0.002}, {0.5, 0.100}, {0.1, nan}};
  const std::vector<bool> front = pareto_front(table);
  EXPECT_EQ(front, (std::vector<bool>{true, false, true, false, true, false}));
  // Two equal points do not dominate each other.
  EXPECT_EQ(pareto_front({{1.0, 1.0}, {1.0, 1.0}}), (std::vector<bool>{true, true}));
}

TEST(AccuracyBench, OneSweepPointRunsEndToEnd) {
  // The fin-ray x rigid scene at dt = 0.02 (two steps per gravity phase), against itself: the
  // errors are measured, the verdicts counted.
  const std::vector<AccuracyScene> scenes = standard_scenes({"fin-ray-rigid"});
  ASSERT_EQ(scenes.size(), 1u);
  const AccuracyScene& scene = scenes.front();
  trial::TrialParameters coarse = scene.parameters;
  coarse.sim.dt = 0.02;
  const SceneRun run = scene.run(coarse, scene.default_mesh, 2);
  ASSERT_EQ(run.outcomes.size(), 3u);
  const int frames = scene.parameters.validation_frames + 1;
  const RunError self = run_error(run.outcomes, run.outcomes, frames, scene.parameters);
  EXPECT_EQ(self.translation, 0.0);
  EXPECT_EQ(self.agreeing, 3);
  for (const trial::TrialOutcome& o : run.outcomes) {
    EXPECT_GT(o.result.record.newton.steps, 0u) << o.failure_reason;
  }
  EXPECT_THROW(standard_scenes({"bimanual"}), std::invalid_argument);
}

}  // namespace
}  // namespace grip::bench
