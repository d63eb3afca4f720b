#include "src/trial/trial_parameters.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "src/config/parameter_table.hpp"
#include "src/scene/sim_parameters.hpp"

namespace grip::trial {

namespace {

using config::Range;
using P = config::Parameter<TrialParameters>;
using T = TrialParameters;

void require(bool ok, const std::string& name, const std::string& what) {
  if (!ok) throw std::invalid_argument("trial parameter " + name + " must be " + what);
}

constexpr double kMaxCount = 1'000'000'000;

constexpr std::array kTrialParameters = {
    P{.key = "placement_gap",
      .real = &T::placement_gap,
      .range = Range::at_least(1),
      .doc = "before the first step each finger moves along its closing path until its surface is "
             "this times d_hat from the object's (or its path ends)"},
    P{.key = "squeeze_speed",
      .real = &T::squeeze_speed,
      .range = Range::positive(),
      .unit = "m/s",
      .doc = "fastest finger speed while closing and servoing its force"},
    P{.key = "grip_force",
      .real = &T::grip_force,
      .range = Range::positive(),
      .unit = "N",
      .doc = "the normal contact force each finger servos to"},
    P{.key = "final_opening",
      .real = &T::final_opening,
      .range = Range::at_least(0),
      .unit = "m",
      .doc = "a parallel gripper's path ends at this opening"},
    P{.key = "finger_stiffness",
      .real = &T::finger_stiffness,
      .range = Range::positive(),
      .unit = "N/m",
      .doc = "after closing, each jaw (or fin-ray finger) acts as a spring of this stiffness "
             "preloaded with its force, standing for its drive's compliance"},
    P{.key = "hand_drive_stiffness",
      .real = &T::hand_drive_stiffness,
      .range = Range::positive(),
      .unit = "N/m",
      .doc = "the hand's finger links follow their joint commands through springs of this "
             "stiffness inside the step (docs/trial.md, \"The hand's drive\")"},
    P{.key = "settle_speed",
      .real = &T::settle_speed,
      .range = Range::positive(),
      .unit = "m/s",
      .doc = "settled (and at rest in a gravity phase) once the object moves slower than this"},
    P{.key = "settle_angular_speed",
      .real = &T::settle_angular_speed,
      .range = Range::positive(),
      .unit = "rad/s",
      .doc = "... and turns slower than this"},
    P{.key = "force_tolerance",
      .real = &T::force_tolerance,
      .range = Range::strictly_between(0, 1),
      .doc = "of grip_force: closing ends when every finger's force is within this of grip_force; "
             "settled when no finger's force changes by more over a step"},
    P{.key = "settle_steps",
      .count = &T::settle_steps,
      .range = Range::from_to(1, kMaxCount),
      .doc = "steps in a row the settled conditions must hold"},
    P{.key = "settle_max_steps",
      .count = &T::settle_max_steps,
      .range = Range::from_to(1, kMaxCount),
      .doc = "a trial not settled within this many steps of closing and settling is `unsettled`"},
    P{.key = "gravity",
      .real = &T::gravity_magnitude,
      .range = Range::positive(),
      .unit = "m/s^2",
      .doc = "the gravity test's magnitude, along +x, -x, +y, -y, +z, -z in turn"},
    P{.key = "phase_duration",
      .real = &T::phase_duration,
      .range = Range::positive(),
      .unit = "s",
      .doc = "each gravity phase (the paper's 0.1 s)"},
    P{.key = "rest_duration",
      .real = &T::rest_duration,
      .range = Range::at_least(0),
      .unit = "s",
      .doc = "the most a gravity phase waits beyond phase_duration for the object to come to rest "
             "(docs/trial.md, \"Verdict\")"},
    P{.key = "displacement_factor",
      .real = &T::displacement_factor,
      .range = Range::positive(),
      .doc = "the verdict's threshold: this x eps_v x dt (the paper's 1 mm), plus eps_v x the time "
             "under gravity (docs/trial.md, \"Verdict\")"},
    P{.key = "object_damping",
      .real = &T::object_damping,
      .range = Range::at_least(0),
      .unit = "s",
      .doc = "a soft object's Rayleigh damping beta (docs/trial.md, \"Why soft objects damp\")",
      .must = "a non-negative time (s, Rayleigh beta)"},
    // At most kMaxMetricSamples: a limit of what a trial holds, checked with its own message.
    P{.key = "metric_samples",
      .count = &T::metric_samples,
      .range = Range::at_least(1),
      .doc = "D1/D2 points sampled on the gripper's surface (24 bytes a point, held per hand and "
             "for the gripper as a whole)"},
    P{.key = "finger_friction",
      .real = &T::rigid_finger_friction,
      .range = Range::at_least(0),
      .doc = "friction coefficient of rigid fingers and hand links; a pair's is sqrt(mu_object "
             "mu_finger)"},
    // With closing_frames + validation_frames at most kMaxTrialFrames (validate()).
    P{.key = "closing_frames",
      .count = &T::closing_frames,
      .range = Range::at_least(2),
      .doc = "frames over closing and settling",
      .section = "outputs"},
    P{.key = "validation_frames",
      .count = &T::validation_frames,
      .range = Range::at_least(6),
      .doc = "frames over the six gravity phases (a multiple of 6)",
      .section = "outputs"},
};

}  // namespace

config::ParameterTable<TrialParameters> trial_parameter_table() { return kTrialParameters; }

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
  config::check_parameters(scene::sim_parameter_table(), p.sim, "physics parameter");
  config::check_parameters(trial_parameter_table(), p, "trial parameter");
  require(p.metric_samples <= kMaxMetricSamples, "metric_samples",
          "at most " + std::to_string(kMaxMetricSamples));
  require(p.settle_max_steps >= p.settle_steps, "settle_max_steps", "at least settle_steps");
  require(p.phase_duration >= p.sim.dt, "phase_duration", "at least one time step (s)");
  require(p.validation_frames % 6 == 0, "validation_frames",
          "a multiple of 6 (equal parts per gravity phase)");
  require(p.closing_frames + static_cast<double>(p.validation_frames) <= kMaxTrialFrames,
          "closing_frames + validation_frames", "at most " + std::to_string(kMaxTrialFrames));
  require(max_trial_steps(p) <= static_cast<double>(kMaxTrialSteps),
          "settle_max_steps + 6 phase_duration / sim.dt",
          "at most " + std::to_string(kMaxTrialSteps) + " steps");
}

}  // namespace grip::trial
