#pragma once
// The grasp trial protocol's settings (GRIP, Sec. III-D): closing, settling, the six-axis
// gravity test, the verdict's threshold, the recorded frames and the D1/D2 sampling, and their
// parameter table (a job file's [trial] and [outputs] keys, grip trial's options, the dataset's
// provenance, docs/job-format.md). docs/trial.md gives each default and why.
#include <Eigen/Core>
#include <array>
#include <cstdint>

#include "solver/scene/scene.hpp"
#include "src/config/parameter.hpp"

namespace grip::trial {

// Gravity directions of the six validation phases, in order (world).
inline const std::array<Eigen::Vector3d, 6> kGravityAxes = {
    Eigen::Vector3d::UnitX(),  -Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
    -Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ(),  -Eigen::Vector3d::UnitZ()};

struct TrialParameters {
  // The solver's settings; `sim.gravity` is ignored (the protocol sets gravity per phase).
  solver::SimParameters sim;

  // Placement: before the first step each finger moves along its closing path until its surface
  // is placement_gap * d_hat from the object's (exact distances), or to the end of its path.
  double placement_gap = 1.5;  // x d_hat
  // Closing, on the object held where the candidate found it: each finger approaches at
  // squeeze_speed until it touches the object or its path ends (a parallel gripper's at
  // final_opening, a hand finger's at a joint limit), then servos its travel so that its normal
  // contact force with the object settles on grip_force (at most squeeze_speed either way).
  // Closing ends when every finger is within force_tolerance of grip_force or at the end of
  // its path: the object is released, and from then on each finger acts as a spring of
  // finger_stiffness preloaded with its force, standing for its drive's compliance.
  double squeeze_speed = 0.01;    // m/s per finger
  double grip_force = 50.0;       // N per finger
  double final_opening = 0.002;   // m
  double finger_stiffness = 2e4;  // N/m: 50 N over 2.5 mm
  // The hand's finger links are driven bodies (solver BodyDescription::drive_stiffness): each
  // follows the pose its joint commands give through a spring of this stiffness inside the
  // step, from the first step to the last, instead of being held a step behind. 2e5 N/m (50 N
  // over 0.25 mm) is the stiffest of those measured that keeps the hand's verdicts at dt/2,
  // newton_tol/10 and two friction lag iterations (docs/trial.md, "The hand's drive").
  double hand_drive_stiffness = 2e5;  // N/m

  // Settling, gravity off, fingers held by their springs: done once the object moves slower than
  // settle_speed and turns slower than settle_angular_speed, and no finger's force changes by more
  // than force_tolerance * grip_force over a step, for settle_steps steps in a row. A trial that
  // does not get there within settle_max_steps steps of closing and settling is `unsettled`.
  double settle_speed = 5e-3;         // m/s
  double settle_angular_speed = 0.1;  // rad/s
  double force_tolerance = 0.05;      // relative to grip_force
  int settle_steps = 3;
  int settle_max_steps = 200;

  // Gravity test: gravity_magnitude along +x, -x, +y, -y, +z, -z (world), phase_duration each
  // (the paper's 0.1 s). A phase whose object is not still by then (slower than settle_speed
  // and settle_angular_speed, settle_steps steps in a row) keeps its gravity until it is, for at
  // most rest_duration more: the slip is measured on an object at rest in the fingers where it
  // comes to rest, not at a random point of a swing; one still swinging when the wait ends is
  // judged by its slip there (docs/trial.md, "Verdict").
  double gravity_magnitude = 9.8;  // m/s^2
  double phase_duration = 0.1;     // s
  double rest_duration = 0.5;      // s

  // Verdict: held if the object still touches a finger at the last step and, at the end of
  // every gravity phase k, it has slipped less than slip_threshold(t_k) from the settled grasp,
  // t_k the time it has spent under gravity by then: displacement_factor * eps_v * dt (the
  // paper's threshold, 1 mm at its eps_v and dt) plus eps_v * t_k, how far IPC's static
  // friction lets a held contact creep in that time (docs/trial.md, "Verdict").
  double displacement_factor = 100.0;
  double displacement_threshold() const { return displacement_factor * sim.eps_v * sim.dt; }
  double slip_threshold(double seconds_under_gravity) const {
    return displacement_threshold() + sim.eps_v * seconds_under_gravity;
  }

  // A soft object's Rayleigh damping beta (solver::Material::damping), as the fin-ray's TPU:
  // real soft materials dissipate, and without it a soft object's swing dies out only by the
  // integrator's damping, which halves with dt (docs/trial.md, "Why soft objects damp").
  double object_damping = 5e-3;  // s

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

// The most steps one trial may take, and the most frames it may record (closing + validation;
// every frame holds every vertex of the scene): job files and validate() refuse more.
inline constexpr std::int64_t kMaxTrialSteps = 10'000'000;
inline constexpr int kMaxTrialFrames = 10'000;
// The most surface points D1/D2 may sample per gripper surface (the paper's 50,000 x 200): each
// trial holds them, 24 bytes a point, per hand and for the gripper as a whole.
inline constexpr int kMaxMetricSamples = 10'000'000;

// The most steps a trial takes: settle_max_steps of closing and settling, then six gravity
// phases of at most round((phase_duration + rest_duration) / dt) steps each; in double, so that
// no setting overflows it.
double max_trial_steps(const TrialParameters& parameters);
// A gravity phase's steps at full length (at least 1), and the most it may add waiting for rest.
double phase_steps(const TrialParameters& parameters);
double rest_steps(const TrialParameters& parameters);

// The largest, over the first `phases` gravity phases, of the slip at a phase's end over the
// verdict's threshold for the time under gravity by then (slip_threshold): at least 1 if the
// grasp slipped. displacement and phase_seconds are the record's, NaN for phases not run
// (left out); NaN if no phase ran.
double slip_over_threshold(const TrialParameters& parameters,
                           const std::array<double, 6>& displacement,
                           const std::array<double, 6>& phase_seconds, int phases = 6);
inline bool slipped_beyond_threshold(const TrialParameters& parameters,
                                     const std::array<double, 6>& displacement,
                                     const std::array<double, 6>& phase_seconds, int phases = 6) {
  return slip_over_threshold(parameters, displacement, phase_seconds, phases) >= 1.0;
}

// Every setting but `sim` (scene::sim_parameter_table's) and metric_seed: the keys of a job
// file's [trial] table, and the frame counts of its [outputs] table (section "outputs").
config::ParameterTable<TrialParameters> trial_parameter_table();

// Throws std::invalid_argument naming the first setting that is out of range (the solver's
// included), or the first pair that contradicts itself.
void validate(const TrialParameters& parameters);

}  // namespace grip::trial
