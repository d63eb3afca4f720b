// Coulomb friction on an incline: sticking above the critical coefficient (creeping at the
// speed IPC's smoothed static friction predicts), sliding with acceleration
// g (sin theta - mu cos theta) below it. (A soft object held by mu = 3.5: test_contact.cpp.)
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tests/solver/scene_builders.hpp"

namespace grip::solver::testing {
namespace {

constexpr double kGravity = 9.81;

// A 4 cm affine box resting on a kinematic ramp tilted by theta about y; gravity along -z.
// Returns the environment and the unit downhill direction.
struct Incline {
  std::unique_ptr<Environment> env;
  Eigen::Vector3d downhill;
};

Incline make_incline(double theta, double mu) {
  const Eigen::Quaterniond tilt(Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitY()));
  return {std::make_unique<Environment>(Model::build(box_on_ramp(theta, mu, 500.0, 0.005))),
          tilt * Eigen::Vector3d::UnitX()};
}

TEST(Friction, BoxSticksWhenMuExceedsTanTheta) {
  const double theta = 20.0 * std::numbers::pi / 180.0;  // tan = 0.364
  Incline incline = make_incline(theta, 0.5);
  run_checked(*incline.env, 40);  // 0.2 s to land and settle
  const Eigen::Vector3d settled = incline.env->center_of_mass(1);
  run_checked(*incline.env, 160, [&](int) {
    // Static friction is smoothed below eps_v: it may creep, never faster than eps_v.
    EXPECT_LT(incline.env->center_of_mass_velocity(1).norm(), 1e-3);
  });
  EXPECT_LT((incline.env->center_of_mass(1) - settled).norm(), 1e-3);
}

TEST(Friction, BelowTheLimitABoxCreepsAtTheSpeedOfIpcsSmoothedStaticFriction) {
  // IPC's static friction is smoothed: f1(v) = 2 v / eps_v - v^2 / eps_v^2 of mu N below eps_v.
  // A box whose downhill load is r = tan(theta) / mu of mu N therefore creeps at the speed where
  // f1 = r: v = eps_v (1 - sqrt(1 - r)), however long it is loaded. The trial's verdict allows
  // for this creep (docs/trial.md, "Verdict").
  const double mu = 0.5;
  const double eps_v = SimParameters{}.eps_v;
  for (const double r : {0.1, 0.5, 0.9}) {
    const double theta = std::atan(r * mu);
    Incline incline = make_incline(theta, mu);
    run_checked(*incline.env, 40);  // 0.2 s to land and settle
    const Eigen::Vector3d start = incline.env->center_of_mass(1);
    run_checked(*incline.env, 100);  // 0.5 s
    const double speed = (incline.env->center_of_mass(1) - start).dot(incline.downhill) / 0.5;
    EXPECT_NEAR(speed, eps_v * (1.0 - std::sqrt(1.0 - r)), 0.02 * eps_v) << "r = " << r;
  }
}

// Slides from rest; the acceleration is measured between 0.3 s and 0.6 s, after any transient.
double measured_acceleration(double theta, double mu) {
  Incline incline = make_incline(theta, mu);
  double v_early = 0.0;
  double v_late = 0.0;
  run_checked(*incline.env, 120, [&](int s) {
    const double v = incline.env->center_of_mass_velocity(1).dot(incline.downhill);
    if (s + 1 == 60) v_early = v;
    if (s + 1 == 120) v_late = v;
  });
  return (v_late - v_early) / 0.3;
}

TEST(Friction, BoxSlidesWithCoulombAcceleration) {
  const double theta = 30.0 * std::numbers::pi / 180.0;  // tan = 0.577
  for (const double mu : {0.1, 0.3, 0.5, 0.55}) {        // 0.55: near the threshold
    const double expected = kGravity * (std::sin(theta) - mu * std::cos(theta));
    const double a = measured_acceleration(theta, mu);
    EXPECT_NEAR(a, expected, 0.05 * expected) << "mu = " << mu;
  }
}

}  // namespace
}  // namespace grip::solver::testing
