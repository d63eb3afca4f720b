// What the trial tests share: the paper's protocol shortened so that a trial takes seconds, the
// one-layer fin-ray gripper, a trial's largest slip, and candidates made of grasps.
#pragma once

#include <algorithm>
#include <array>
#include <vector>

#include "src/grippers/parallel_gripper.hpp"
#include "src/synth/candidate.hpp"
#include "src/trial/hand_trial_scene.hpp"
#include "src/trial/parallel_trial_scene.hpp"
#include "src/trial/trial_parameters.hpp"

namespace grip::trial::testing {

// The paper's protocol with shorter gravity phases (5 steps), fewer recorded frames and D1/D2
// points.
inline TrialParameters short_parameters() {
  TrialParameters p;
  p.phase_duration = 0.05;
  p.closing_frames = 8;
  p.validation_frames = 12;
  p.metric_samples = 20000;
  return p;
}

// grip's 80 mm fin-ray finger with one tet layer across its depth instead of four (same
// profile).
inline const grippers::ParallelGripper& one_layer_fin_ray() {
  static const grippers::ParallelGripper gripper = [] {
    grippers::FinRayOptions options = grippers::fin_ray_80mm_options();
    options.layers = 1;
    return grippers::make_umi_soft_gripper(options);
  }();
  return gripper;
}

inline double largest(const std::array<double, 6>& values) {
  return *std::max_element(values.begin(), values.end());
}

// Candidates of one parallel gripper each, or of two (bimanual, the first gripper's first).
inline std::vector<synth::Candidate> parallel_candidates(const std::vector<ParallelGrasp>& grasps) {
  std::vector<synth::Candidate> candidates;
  for (const ParallelGrasp& grasp : grasps) candidates.push_back(parallel_candidate({grasp}));
  return candidates;
}
inline std::vector<synth::Candidate> bimanual_candidates(
    const std::vector<std::array<ParallelGrasp, 2>>& grasps) {
  std::vector<synth::Candidate> candidates;
  for (const auto& pair : grasps) candidates.push_back(parallel_candidate({pair[0], pair[1]}));
  return candidates;
}

// Candidates of one hand each, or of two (the right hand first).
inline std::vector<synth::Candidate> hand_candidates(const std::vector<HandTrialGrasp>& grasps) {
  std::vector<synth::Candidate> candidates(grasps.size());
  for (std::size_t k = 0; k < grasps.size(); ++k) candidates[k].hands = {grasps[k]};
  return candidates;
}
inline std::vector<synth::Candidate> bimanual_hand_candidates(
    const std::vector<std::array<HandTrialGrasp, 2>>& grasps) {
  std::vector<synth::Candidate> candidates(grasps.size());
  for (std::size_t k = 0; k < grasps.size(); ++k) {
    candidates[k].hands = {grasps[k][0], grasps[k][1]};
  }
  return candidates;
}

}  // namespace grip::trial::testing
