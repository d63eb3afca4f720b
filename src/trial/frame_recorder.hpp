#pragma once
// Picks and keeps a trial's recorded frames: `closing` frames spread evenly over closing and
// settling, whose length is not known in advance (kept with a doubling stride, so at most
// 2 x closing frames are held), and `validation` frames spread evenly over each gravity phase.
#include <array>
#include <vector>

#include "io/candidate_record.hpp"
#include "src/trial/trial_outcome.hpp"

namespace grip::trial {

// One recorded state, in the dataset's layout.
struct RecordedFrame {
  std::vector<float> object_vertices;          // n x 3
  std::vector<float> gripper_vertices;         // g x 3
  std::vector<float> contact_forces;           // n x 3, N: barrier force on each object vertex
  std::vector<float> friction_forces;          // n x 3, N: friction force of the last step
  std::vector<float> gripper_contact_forces;   // g x 3, N: the same on the gripper's vertices
  std::vector<float> gripper_friction_forces;  // g x 3, N
  std::array<double, 12> object_pose{};
  std::vector<double> hand_poses;  // 12 per gripper (hand)
  std::vector<double> joints;      // the grippers' joint values, one gripper after the other
  BodyFrame bodies;                // filled only when body frames are kept
};

class FrameRecorder {
 public:
  FrameRecorder(int closing_frames, int validation_frames, int steps_per_phase);

  // Closing and settling: hand the initial state (before the first step) to add_closing(),
  // call closing_step() after each step and, when it returns true, hand that step's state to
  // add_closing(); at the end hand the settled state to add_settled() (always the last
  // closing frame).
  bool closing_step();
  void add_closing(RecordedFrame frame);
  void add_settled(RecordedFrame frame);

  // Gravity phases: validation_due(step in phase, 1-based) says whether that step's state is
  // a validation frame.
  bool validation_due(int step_in_phase) const;
  void add_validation(RecordedFrame frame);

  // closing_frames + validation_frames frames: closing frames picked evenly (first and last
  // included), then the validation frames; a trial that ended early repeats its last frame.
  // The settled state is optional (a trial that failed while closing has none).
  std::vector<RecordedFrame> frames() const;
  // How many of frames() hold states the trial reached: the closing frames and the validation
  // frames recorded so far (0 before the first frame); the rest repeat the last of them.
  int simulated_frames() const;

 private:
  int closing_frames_;
  int validation_frames_;
  int steps_per_phase_;
  int frames_per_phase_;
  long closing_steps_ = 0;
  long stride_ = 1;
  std::vector<RecordedFrame> closing_;
  std::vector<long> closing_step_of_;  // the closing step each kept frame was taken at
  std::vector<RecordedFrame> validation_;
};

// The dataset's trajectory of `frames` (one hand).
io::TrajectoryRecord trajectory_record(const std::vector<RecordedFrame>& frames);

}  // namespace grip::trial
