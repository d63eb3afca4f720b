#include "src/trial/trial_parameters.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace grip::trial {

namespace {

void require(bool ok, const std::string& name, const std::string& what) {
  if (!ok) throw std::invalid_argument("trial parameter " + name + " must be " + what);
}

}  // namespace

double phase_steps(const TrialParameters& p) {
  return std::max(1.0, std::round(p.phase_duration / p.sim.dt));
}

double rest_steps(const TrialParameters& p) { return std::round(p.rest_duration / p.sim.dt); }

double max_trial_steps(const TrialParameters& p) {
  return p.settle_max_steps + 6.0 * (phase_steps(p) + rest_steps(p));
}

double slip_over_threshold(const TrialParameters& p, const std::array<double, 6>& displacement,
                           const std::array<double, 6>& phase_seconds, int phases) {
  double seconds = 0.0;
  double largest = std::numeric_limits<double>::quiet_NaN();
  for (int k = 0; k < phases; ++k) {
    seconds += phase_seconds[k];
    const double ratio = displacement[k] / p.slip_threshold(seconds);
    if (!std::isnan(ratio)) largest = std::isnan(largest) ? ratio : std::max(largest, ratio);
  }
  return largest;
}

void validate(const TrialParameters& p) {
  require(p.sim.dt > 0.0 && std::isfinite(p.sim.dt), "sim.dt", "a positive time step (s)");
  require(p.sim.eps_v > 0.0, "sim.eps_v", "positive (m/s)");
  require(p.placement_gap >= 1.0 && std::isfinite(p.placement_gap), "placement_gap",
          "at least 1 (a multiple of d_hat)");
  require(p.squeeze_speed > 0.0 && std::isfinite(p.squeeze_speed), "squeeze_speed",
          "positive (m/s)");
  require(p.grip_force > 0.0 && std::isfinite(p.grip_force), "grip_force", "positive (N)");
  require(p.final_opening >= 0.0, "final_opening", ">= 0 (m)");
  require(p.finger_stiffness > 0.0 && std::isfinite(p.finger_stiffness), "finger_stiffness",
          "positive (N/m)");
  require(p.hand_drive_stiffness > 0.0 && std::isfinite(p.hand_drive_stiffness),
          "hand_drive_stiffness", "positive (N/m)");
  require(p.settle_speed > 0.0, "settle_speed", "positive (m/s)");
  require(p.settle_angular_speed > 0.0, "settle_angular_speed", "positive (rad/s)");
  require(p.force_tolerance > 0.0 && p.force_tolerance < 1.0, "force_tolerance",
          "between 0 and 1 (relative to grip_force)");
  require(p.settle_steps >= 1, "settle_steps", "at least 1");
  require(p.settle_max_steps >= p.settle_steps, "settle_max_steps", "at least settle_steps");
  require(p.gravity_magnitude >= 0.0, "gravity_magnitude", ">= 0 (m/s^2)");
  require(p.phase_duration >= p.sim.dt, "phase_duration", "at least one time step (s)");
  require(p.rest_duration >= 0.0 && std::isfinite(p.rest_duration), "rest_duration", ">= 0 (s)");
  require(p.displacement_factor > 0.0, "displacement_factor", "positive");
  require(p.object_damping >= 0.0 && std::isfinite(p.object_damping), "object_damping", ">= 0 (s)");
  require(p.closing_frames >= 2, "closing_frames", "at least 2");
  require(p.validation_frames >= 6 && p.validation_frames % 6 == 0, "validation_frames",
          "a positive multiple of 6 (equal parts per gravity phase)");
  require(p.closing_frames + static_cast<double>(p.validation_frames) <= kMaxTrialFrames,
          "closing_frames + validation_frames", "at most " + std::to_string(kMaxTrialFrames));
  require(max_trial_steps(p) <= static_cast<double>(kMaxTrialSteps),
          "settle_max_steps + 6 phase_duration / sim.dt",
          "at most " + std::to_string(kMaxTrialSteps) + " steps");
  require(p.metric_samples >= 1 && p.metric_samples <= kMaxMetricSamples, "metric_samples",
          "from 1 to " + std::to_string(kMaxMetricSamples));
  require(p.rigid_finger_friction >= 0.0, "rigid_finger_friction", ">= 0");
}

}  // namespace grip::trial
