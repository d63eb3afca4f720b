#include "src/trial/finger_servo.hpp"

#include <algorithm>

namespace grip::trial {

FingerServo::FingerServo(double travel, double max_travel, double target, double tolerance)
    : start_(travel),
      travel_(travel),
      max_travel_(max_travel),
      target_(target),
      tolerance_(tolerance) {}

void FingerServo::observe(double force) {
  const bool same_side = (force < target_) == (force_ < target_) && (force > 0.0) == (force_ > 0.0);
  same_side_ = same_side ? same_side_ + 1 : 0;
  // The secant of two samples in contact and apart in travel: the finger's stiffness as the
  // servo sees it (a non-positive one, the object moving under the finger, is not kept).
  const double moved = travel_ - travel_at_force_;
  if (force > 0.0 && force_ > 0.0 && std::abs(moved) > 1e-9 && (force - force_) / moved > 0.0) {
    stiffness_ = (force - force_) / moved;
  }
  travel_at_force_ = travel_;
  previous_force_ = force_;
  force_ = force;
  ++observations_;
  touched_ = touched_ || force > 0.0;
  if (!touched_) return;
  Sample& side = force < target_ ? below_ : above_;
  side = {travel_, force, observations_};
  // The object moved under the finger: a bracket that no longer closes (more force further
  // out) keeps only its newer side.
  if (below_.known() && above_.known() && below_.travel >= above_.travel) {
    (force < target_ ? above_ : below_) = Sample{};
  }
}

void FingerServo::hold_as_spring(double stiffness) {
  spring_stiffness_ = stiffness;
  spring_rest_ = travel_ + force_ / stiffness;
}

double FingerServo::spring_increment(double max_step) const {
  const double spring = spring_stiffness_ * (spring_rest_ - travel_);
  double next = spring_rest_;  // out of contact: the spring relaxes
  if (force_ > 0.0) {
    // Half a Newton step on force - spring = 0, the contact's stiffness taken from the last
    // secant; without one, a quarter of max_step towards balance.
    const double excess = force_ - spring;
    next = stiffness_ > 0.0 ? travel_ - 0.5 * excess / (stiffness_ + spring_stiffness_)
                            : travel_ - std::copysign(kTouchedStepFraction * max_step, excess);
  }
  return on_path(std::clamp(next - travel_, -max_step, max_step));
}

double FingerServo::next_increment(double max_step) const {
  if (halted_) return 0.0;
  if (spring_stiffness_ > 0.0) return spring_increment(max_step);
  // Once the finger has touched, from a quarter of max_step: within d_hat the barrier's force
  // goes from zero to hundreds of newtons over a few tenths of a millimetre.
  const double step =
      touched_ ? std::min(1.0, kTouchedStepFraction * std::ldexp(1.0, std::min(same_side_, 2))) *
                     max_step
               : max_step;
  double next = travel_;
  if (!(force_ > 0.0)) {
    next = travel_ + step;
  } else if (std::abs(target_ - force_) > 0.25 * tolerance_) {
    const auto fresh = [&](const Sample& s) {
      return s.known() && observations_ - s.observation < kBracketAge;
    };
    if (fresh(below_) && fresh(above_) && above_.travel - below_.travel > 1e-9) {
      const double width = above_.travel - below_.travel;
      const double fraction = (target_ - below_.force) / (above_.force - below_.force);
      // Inside the bracket, off its ends (regula falsi alone can creep along one side).
      next = below_.travel + width * std::clamp(fraction, 0.1, 0.9);
      next = std::clamp(next, travel_ - step, travel_ + step);
    } else if (stiffness_ > 0.0) {
      // Half the secant step: a compliant finger (the fin-ray bends by centimetres before it
      // pushes with 50 N) moves faster than squeeze_speed, a rigid contact far slower.
      const double reach = kFastSteps * max_step;
      next = travel_ + std::clamp(0.5 * (target_ - force_) / stiffness_, -reach, reach);
    } else {
      next = travel_ + (force_ < target_ ? step : -step);
    }
  }
  return on_path(next - travel_);
}

double FingerServo::on_path(double increment) const {
  return std::clamp(travel_ + increment, std::min(start_, travel_), max_travel_) - travel_;
}

void FingerServo::advance(double increment) { travel_ += increment; }

}  // namespace grip::trial
