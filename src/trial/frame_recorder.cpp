#include "src/trial/frame_recorder.hpp"

#include <cmath>
#include <utility>

namespace grip::trial {

FrameRecorder::FrameRecorder(int closing_frames, int validation_frames, int steps_per_phase)
    : closing_frames_(closing_frames),
      validation_frames_(validation_frames),
      steps_per_phase_(steps_per_phase),
      frames_per_phase_(validation_frames / 6) {}

bool FrameRecorder::closing_step() { return ++closing_steps_ % stride_ == 0; }

void FrameRecorder::add_closing(RecordedFrame frame) {
  closing_.push_back(std::move(frame));
  closing_step_of_.push_back(closing_steps_);
  if (static_cast<int>(closing_.size()) < 2 * closing_frames_) return;
  // Full: keep every other frame (the first included) and record half as often.
  std::vector<RecordedFrame> kept;
  std::vector<long> kept_steps;
  for (std::size_t i = 0; i < closing_.size(); i += 2) {
    kept.push_back(std::move(closing_[i]));
    kept_steps.push_back(closing_step_of_[i]);
  }
  closing_ = std::move(kept);
  closing_step_of_ = std::move(kept_steps);
  stride_ *= 2;
}

void FrameRecorder::add_settled(RecordedFrame frame) {
  // The settled state replaces a frame taken at the same step rather than repeating it.
  if (!closing_.empty() && closing_step_of_.back() == closing_steps_) {
    closing_.back() = std::move(frame);
  } else {
    closing_.push_back(std::move(frame));
    closing_step_of_.push_back(closing_steps_);
  }
}

bool FrameRecorder::validation_due(int step_in_phase) const {
  // The k-th frame of a phase is the step at which floor(step * frames / steps) reaches k.
  const long before = static_cast<long>(step_in_phase - 1) * frames_per_phase_ / steps_per_phase_;
  const long now = static_cast<long>(step_in_phase) * frames_per_phase_ / steps_per_phase_;
  return now > before;
}

void FrameRecorder::add_validation(RecordedFrame frame) { validation_.push_back(std::move(frame)); }

std::vector<RecordedFrame> FrameRecorder::frames() const {
  std::vector<RecordedFrame> frames;
  if (closing_.empty()) return frames;
  const double last = static_cast<double>(closing_.size() - 1);
  for (int i = 0; i < closing_frames_; ++i) {
    const auto pick = static_cast<std::size_t>(std::lround(i * last / (closing_frames_ - 1)));
    frames.push_back(closing_[pick]);
  }
  for (int i = 0; i < validation_frames_; ++i) {
    frames.push_back(i < static_cast<int>(validation_.size()) ? validation_[i]
                     : validation_.empty()                    ? closing_.back()
                                                              : validation_.back());
  }
  return frames;
}

int FrameRecorder::simulated_frames() const {
  if (closing_.empty()) return 0;
  return closing_frames_ + static_cast<int>(validation_.size());
}

io::TrajectoryRecord trajectory_record(const std::vector<RecordedFrame>& frames) {
  io::TrajectoryRecord record;
  const auto append = [](std::vector<float>& to, const std::vector<float>& from) {
    to.insert(to.end(), from.begin(), from.end());
  };
  for (const RecordedFrame& frame : frames) {
    append(record.object_vertices, frame.object_vertices);
    append(record.gripper_vertices, frame.gripper_vertices);
    append(record.contact_forces, frame.contact_forces);
    append(record.friction_forces, frame.friction_forces);
    append(record.gripper_contact_forces, frame.gripper_contact_forces);
    append(record.gripper_friction_forces, frame.gripper_friction_forces);
    record.object_poses.insert(record.object_poses.end(), frame.object_pose.begin(),
                               frame.object_pose.end());
    record.hand_poses.insert(record.hand_poses.end(), frame.hand_poses.begin(),
                             frame.hand_poses.end());
    record.joints.insert(record.joints.end(), frame.joints.begin(), frame.joints.end());
  }
  return record;
}

}  // namespace grip::trial
