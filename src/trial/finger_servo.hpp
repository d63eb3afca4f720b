#pragma once
// One finger's squeeze: its travel along the closing path, servoed so that its normal contact
// force with the object settles on the grip force, then held as a spring (docs/trial.md,
// "Force control" and "Fingers on springs after closing").
#include <cmath>
#include <limits>

namespace grip::trial {

class FingerServo {
 public:
  // `travel` where placement left the finger, `max_travel` where its path ends (m); the force
  // it servos to and the tolerance it is held within (N).
  FingerServo(double travel, double max_travel, double target, double tolerance);

  // The finger's force with the object after a step (N).
  void observe(double force);

  // The travel change over the next step (m): the approach at `max_step` until the first
  // contact (and at a quarter of it after losing contact, doubling while it stays lost); none
  // while the force is within a quarter of the tolerance of the target (so that it settles near
  // the target, not at the edge of the tolerance); otherwise regula falsi between the latest
  // travels whose forces fell below and rose above the target (the barrier's force grows by orders
  // of magnitude within d_hat, so a bracket is what keeps the servo from hunting), or, while one
  // side of the bracket is missing or stale (the object moves under the fingers, so a sample older
  // than kBracketAge observations no longer says where the force is): half the secant step on the
  // last two samples in contact, at most kFastSteps x max_step (a compliant finger needs
  // centimetres of travel), or without a secant a quarter of max_step, doubled at each observation
  // the force stays on one side of the target, up to max_step. Never past the end of the path, nor
  // back past where the finger started. Held as a spring, spring_increment's instead.
  double next_increment(double max_step) const;
  // After closing: from now on the finger acts as a spring of `stiffness` (N/m) preloaded with
  // its force now, standing for its drive's compliance. next_increment then moves it (at most
  // max_step a step) so that its contact force matches the spring's.
  void hold_as_spring(double stiffness);
  // After closing, for a finger whose drive is a spring inside the solve: it stays where its
  // command stands.
  void halt() { halted_ = true; }

  // Commits an increment returned by next_increment.
  void advance(double increment);

  double travel() const { return travel_; }
  double force() const { return force_; }
  double previous_force() const { return previous_force_; }
  bool on_target() const { return std::abs(target_ - force_) <= tolerance_; }
  bool at_limit() const { return travel_ >= max_travel_; }

 private:
  struct Sample {
    double travel = std::numeric_limits<double>::quiet_NaN();
    double force = 0.0;
    long observation = 0;
    bool known() const { return !std::isnan(travel); }
  };
  static constexpr long kBracketAge = 4;
  static constexpr double kTouchedStepFraction = 0.25;
  static constexpr double kFastSteps = 4.0;  // a secant step's limit, in max_step

  // The increment of a finger held as a spring: towards contact force = spring force.
  double spring_increment(double max_step) const;
  // `increment` cut to the finger's path (never past its end, nor back past its start).
  double on_path(double increment) const;

  double start_;
  double travel_;
  double max_travel_;
  double target_;
  double tolerance_;
  double force_ = 0.0;
  double previous_force_ = std::numeric_limits<double>::quiet_NaN();
  Sample below_;  // the latest sample whose force was below the target
  Sample above_;  // the latest sample whose force was above it
  bool touched_ = false;
  long observations_ = 0;
  double travel_at_force_ = 0.0;  // the travel force_ was measured at
  double stiffness_ = 0.0;        // N/m, the last positive secant; 0: none yet
  int same_side_ = 0;  // observations in a row on one side of the target (or out of contact)
  double spring_stiffness_ = 0.0;  // N/m; 0: still closing
  double spring_rest_ = 0.0;       // the travel at which the spring's force is zero
  bool halted_ = false;
};

}  // namespace grip::trial
