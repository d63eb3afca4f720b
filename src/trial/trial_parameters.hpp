#pragma once
// The grasp trial protocol's settings (GRIP, Sec. III-D): closing, settling, the six-axis
// gravity test, the verdict's threshold, the recorded frames and the D1/D2 sampling.
// docs/trial.md gives each default and why.
#include <cstdint>

#include "solver/scene.hpp"

namespace grip::trial {

struct TrialParameters {
  // The solver's settings; `sim.gravity` is ignored (the protocol sets gravity per phase).
  solver::SimParameters sim;

  // Closing: each jaw moves at closing_speed towards the other, and at squeeze_speed once its
  // finger touches the object, until the contact force between its finger and the object
  // exceeds stop_force, or until the opening reaches final_opening (a gripper closing on air
  // stops there).
  double closing_speed = 0.05;   // m/s per jaw
  double squeeze_speed = 0.01;   // m/s per jaw
  double stop_force = 50.0;      // N
  double final_opening = 0.002;  // m

  // Settling, gravity off: done once the object's centre of mass moved slower than
  // settle_speed for settle_steps steps in a row, or after settle_max_steps steps.
  double settle_speed = 5e-3;  // m/s
  int settle_steps = 3;
  int settle_max_steps = 50;

  // Gravity test: gravity_magnitude along +x, -x, +y, -y, +z, -z (world), phase_duration each.
  double gravity_magnitude = 9.8;  // m/s^2
  double phase_duration = 0.1;     // s

  // Verdict: held if the object still touches a finger at the last step and its centre of
  // mass moved less than displacement_factor * eps_v * dt from the settled grasp at the end of
  // every gravity phase.
  double displacement_factor = 100.0;
  double displacement_threshold() const { return displacement_factor * sim.eps_v * sim.dt; }

  // Frames recorded per trial: closing (closing and settling, evenly spread) and validation
  // (spread evenly over the six gravity phases; a multiple of 6).
  int closing_frames = 40;
  int validation_frames = 60;

  // D1/D2: points sampled on the fingers' surface (seeded, area-uniform).
  int metric_samples = 50000;
  std::uint64_t metric_seed = 0;

  // Friction coefficient of the rigid jaw gripper's box fingers (the fin-ray finger brings
  // its own); a pair's mu is sqrt(mu_object mu_finger).
  double rigid_finger_friction = 1.0;
};

// Throws std::invalid_argument naming the first setting that is out of range.
void validate(const TrialParameters& parameters);

}  // namespace grip::trial
