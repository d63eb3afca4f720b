#pragma once
// The dataset's description of a trial's gripper (io::GripperRecord): what its joints and
// closing forces mean, and its surface at rest in the vertex order of the recorded frames.
#include "io/gripper_record.hpp"
#include "src/trial/hand_trial_scene.hpp"
#include "src/trial/trial_scene.hpp"

namespace grip::trial {

// A parallel gripper: kind "parallel", one joint ("opening", m), fingers "positive" and
// "negative" (grippers::Jaw), both fingers at the widest opening in the gripper frame. A scene
// of two grippers: hands = 2, named "NAME-bimanual", joint and finger names per gripper, the
// surface once per gripper (each in its own frame).
io::GripperRecord gripper_record(const TrialScene& scene);

// A hand: kind "hand", its joints in degree-of-freedom order (rad), its fingers, every link at
// joints 0 in the hand frame (HandTrialScene::hand_rest_surface). A scene of a right and a left
// hand: hands = 2, named "NAME-bimanual", joint and finger names per hand (the left hand's are
// the right's), then the right hand's surface and the left one's, each in its own hand frame.
// Throws std::invalid_argument for two hands that differ in joints, fingers or surface size.
io::GripperRecord gripper_record(const HandTrialScene& scene);

}  // namespace grip::trial
