#include "src/trial/frame_recorder.hpp"

#include <gtest/gtest.h>

namespace grip::trial {
namespace {

// A frame that carries its step number as its joint value, so a test can see which were kept.
RecordedFrame tagged(double step) {
  RecordedFrame frame;
  frame.joints = {step};
  frame.hand_poses.assign(12, 0.0);
  frame.object_vertices = {float(step), 0.f, 0.f};
  frame.contact_forces = {0.f, float(step), 0.f};
  frame.friction_forces = {0.f, 0.f, float(step)};
  return frame;
}

std::vector<double> openings(const std::vector<RecordedFrame>& frames) {
  std::vector<double> values;
  for (const RecordedFrame& f : frames) values.push_back(f.joints.front());
  return values;
}

TEST(FrameRecorder, SpreadsClosingFramesEvenlyOverAnUnknownLength) {
  // 4 closing frames over 0..100 steps: strides double while the buffer fills, and the picks
  // are evenly spread with the initial and the settled states at the ends.
  FrameRecorder recorder(4, 6, 1);
  recorder.add_closing(tagged(0));
  for (int step = 1; step < 100; ++step) {
    if (recorder.closing_step()) recorder.add_closing(tagged(step));
  }
  recorder.closing_step();
  recorder.add_settled(tagged(100));
  const std::vector<double> picked = openings(recorder.frames());
  ASSERT_EQ(picked.size(), 4u + 6u);
  EXPECT_EQ(picked[0], 0.0);
  EXPECT_EQ(picked[3], 100.0);
  // Interior picks lie near a third and two thirds of the way, within one stride (16 steps).
  EXPECT_NEAR(picked[1], 100.0 / 3, 16.0);
  EXPECT_NEAR(picked[2], 200.0 / 3, 16.0);
  // No validation frames yet: the settled state stands in for all of them.
  for (int i = 4; i < 10; ++i) EXPECT_EQ(picked[i], 100.0);
}

TEST(FrameRecorder, ASettledStateAtARecordedStepReplacesIt) {
  FrameRecorder recorder(2, 6, 1);
  recorder.add_closing(tagged(0));
  recorder.closing_step();  // step 1 (stride 1: recorded)
  recorder.add_closing(tagged(1));
  recorder.add_settled(tagged(1.5));  // the same step: replaces it
  const std::vector<double> picked = openings(recorder.frames());
  EXPECT_EQ(picked[0], 0.0);
  EXPECT_EQ(picked[1], 1.5);
}

TEST(FrameRecorder, ValidationFramesSpreadOverEachPhase) {
  // 2 frames per phase over 10 steps: steps 5 and 10.
  FrameRecorder recorder(2, 12, 10);
  std::vector<int> due;
  for (int s = 1; s <= 10; ++s) {
    if (recorder.validation_due(s)) due.push_back(s);
  }
  EXPECT_EQ(due, (std::vector<int>{5, 10}));
  // As many frames as steps: every step.
  FrameRecorder every(2, 60, 10);
  for (int s = 1; s <= 10; ++s) EXPECT_TRUE(every.validation_due(s));
}

TEST(FrameRecorder, TrajectoryRecordHasTheDatasetLayout) {
  std::vector<RecordedFrame> frames = {tagged(0), tagged(1)};
  frames[1].object_pose[3] = 0.5;
  const io::TrajectoryRecord record = trajectory_record(frames);
  EXPECT_EQ(record.object_vertices.size(), 6u);
  EXPECT_EQ(record.contact_forces, (std::vector<float>{0, 0, 0, 0, 1, 0}));
  EXPECT_EQ(record.friction_forces, (std::vector<float>{0, 0, 0, 0, 0, 1}));
  EXPECT_EQ(record.object_poses.size(), 24u);
  EXPECT_EQ(record.object_poses[12 + 3], 0.5);
  EXPECT_EQ(record.hand_poses.size(), 24u);
  EXPECT_EQ(record.joints, (std::vector<double>{0.0, 1.0}));
}

}  // namespace
}  // namespace grip::trial
