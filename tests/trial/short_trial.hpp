// What the trial tests share: the paper's protocol shortened so that a trial takes seconds, the
// one-layer fin-ray gripper, and a trial's largest slip.
#pragma once

#include <algorithm>
#include <array>

#include "src/grippers/parallel_gripper.hpp"
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

// A fin-ray finger with one tet layer across its depth instead of eight (same profile).
inline const grippers::ParallelGripper& one_layer_fin_ray() {
  static const grippers::ParallelGripper gripper = [] {
    grippers::FinRayOptions options;
    options.layers = 1;
    return grippers::make_umi_soft_gripper(options);
  }();
  return gripper;
}

inline double largest(const std::array<double, 6>& values) {
  return *std::max_element(values.begin(), values.end());
}

}  // namespace grip::trial::testing
