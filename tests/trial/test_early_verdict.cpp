// A trial stops once a gravity phase's end has decided its verdict (the object dropped, or
// slipped past the threshold), and that verdict is the one the whole protocol gives: the same
// candidates run to the end of the six phases (TrialRunOptions::full_trials) agree on every
// verdict, on every phase measured up to the decision, and on the frames recorded up to there.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "src/geometry/primitives.hpp"
#include "src/trial/parallel_trial_scene.hpp"
#include "src/trial/same_result.hpp"
#include "src/trial/trial.hpp"
#include "tests/trial/short_trial.hpp"

namespace grip::trial {
namespace {

using testing::parallel_candidates;
using testing::short_parameters;

// A 4 cm cube between rigid jaws squeezing 50 N each, the jaws' mu set so that its weight along
// them is `load` times what friction holds: held below 1, sliding out above.
TrialOutcome squeezed_cube(double load, bool full_trials) {
  TrialParameters p = short_parameters();
  TrialObject cube;
  cube.name = "cube";
  cube.surface = geometry::make_box(Eigen::Vector3d(0.04, 0.04, 0.04));
  cube.material.density = 1000.0;
  const double weight = cube.material.density * 0.04 * 0.04 * 0.04 * 9.8;
  cube.material.friction = weight / (load * 2.0 * p.grip_force);
  p.rigid_finger_friction = cube.material.friction;
  ParallelGrasp grasp;
  grasp.pose.translation() = Eigen::Vector3d(0.0, 0.0, -0.025);
  grasp.opening = 0.04 + 0.0046;
  static const grippers::ParallelGripper jaws = grippers::make_rigid_jaw_gripper();
  TrialRunOptions options;
  options.full_trials = full_trials;
  return run_trials(ParallelTrialScene(cube, jaws, p), parallel_candidates({grasp}), options)
      .front();
}

TEST(EarlyVerdict, ADecidedTrialStopsWithTheVerdictOfTheWholeProtocol) {
  const TrialParameters p = short_parameters();
  const int frames = p.closing_frames + p.validation_frames;
  const int frames_per_phase = p.validation_frames / 6;
  int stopped_early = 0;
  for (const double load : {0.5, 1.25, 4.0}) {
    SCOPED_TRACE(load);
    const TrialOutcome early = squeezed_cube(load, false);
    const TrialOutcome full = squeezed_cube(load, true);
    const io::CandidateRecord& e = early.result.record;
    const io::CandidateRecord& f = full.result.record;
    EXPECT_EQ(e.status, f.status);
    EXPECT_EQ(e.failure, f.failure)
        << io::to_string(e.failure) << " / " << io::to_string(f.failure);
    EXPECT_TRUE(early.failure_reason.empty()) << early.failure_reason;
    EXPECT_EQ(f.simulated_frames, static_cast<std::uint32_t>(frames));
    if (e.failure == io::FailureKind::kNone) {
      // A held grasp is decided only by the last phase: the two runs are the same run.
      EXPECT_TRUE(same_result(early.result, full.result));
      EXPECT_EQ(e.simulated_frames, static_cast<std::uint32_t>(frames));
      continue;
    }
    ASSERT_TRUE(e.failure == io::FailureKind::kDisplaced ||
                e.failure == io::FailureKind::kLostContact)
        << io::to_string(e.failure);
    // The phases up to the deciding one are measured alike; none after it is run.
    int decided = 0;
    while (decided < 5 && !std::isnan(e.phase_seconds[decided + 1])) ++decided;
    for (int k = 0; k <= decided; ++k) {
      EXPECT_EQ(e.displacement[k], f.displacement[k]) << "phase " << k;
      EXPECT_EQ(e.phase_seconds[k], f.phase_seconds[k]) << "phase " << k;
    }
    for (int k = decided + 1; k < 6; ++k) {
      EXPECT_TRUE(std::isnan(e.displacement[k])) << "phase " << k;
      EXPECT_FALSE(std::isnan(f.phase_seconds[k])) << "phase " << k;
    }
    EXPECT_GE(slip_over_threshold(p, e.displacement, e.phase_seconds), 1.0);
    // The frames up to the decision are the full run's; the rest repeat the last of them.
    const auto simulated = static_cast<std::size_t>(e.simulated_frames);
    EXPECT_EQ(simulated,
              static_cast<std::size_t>(p.closing_frames + frames_per_phase * (decided + 1)));
    const std::vector<double>& ep = early.result.trajectory->object_poses;
    const std::vector<double>& fp = full.result.trajectory->object_poses;
    ASSERT_EQ(ep.size(), fp.size());
    for (std::size_t i = 0; i < 12 * simulated; ++i) EXPECT_EQ(ep[i], fp[i]) << "value " << i;
    for (std::size_t i = 12 * simulated; i < ep.size(); ++i) {
      EXPECT_EQ(ep[i], ep[12 * (simulated - 1) + i % 12]) << "value " << i;
    }
    EXPECT_LT(e.newton.steps, f.newton.steps);
    stopped_early += decided < 5;
  }
  EXPECT_GE(stopped_early, 1) << "no trial was decided before its last phase";
}

}  // namespace
}  // namespace grip::trial
