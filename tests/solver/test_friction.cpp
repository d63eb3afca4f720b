// Coulomb friction on an incline: sticking above the critical coefficient, sliding with
// acceleration g (sin theta - mu cos theta) below it, and a soft squeeze held by mu = 3.5.
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
