#pragma once
// A candidate on which grip and MuJoCo disagree, written for a look in ParaView or
// plot_peer_grasp.py: grip's trial frames and MuJoCo's settled and final grasp as VTK series over
// the same bodies (trial::write_vtk_series).
#include <filesystem>
#include <string>

#include "bench/peer/mujoco_hand_trial.hpp"
#include "bench/peer/mujoco_trial.hpp"
#include "src/synth/candidate.hpp"
#include "src/trial/hand_trial_scene.hpp"

namespace grip::bench {

// Runs grip's trial of `grasp` on `object` again, recording every body in a few frames of
// closing and settling (the settled grasp among them) and one per gravity phase, and writes
// DIR/STEM_grip.pvd and DIR/STEM_mujoco.pvd (frame 0: MuJoCo's settled grasp, frame 1: its end),
// with their .vtu files. Throws std::runtime_error naming a file it cannot write.
void write_peer_hand_vtk(const std::filesystem::path& dir, const std::string& stem,
                         const trial::TrialObject& object, const trial::HandTrialScene& scene,
                         const trial::HandTrialGrasp& grasp, const MujocoHandOutcome& mujoco,
                         int threads);

// The same for a parallel gripper's candidate (rigid jaws or fin-ray): the bodies are the
// object, then per jaw its jaw block and finger (a soft finger's tets as MuJoCo's flex moved
// them).
void write_peer_jaws_vtk(const std::filesystem::path& dir, const std::string& stem,
                         const trial::TrialObject& object, const grippers::ParallelGripper& gripper,
                         const synth::HandGrasp& grasp, const MujocoOutcome& mujoco,
                         const trial::TrialParameters& parameters, int threads);

}  // namespace grip::bench
