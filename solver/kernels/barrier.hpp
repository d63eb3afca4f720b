#pragma once
// IPC's log barrier on squared distances: b(d, d_hat) = -(d - d_hat)^2 ln(d / d_hat) for
// 0 < d < d_hat and 0 beyond, where d and d_hat are both SQUARED distances (as ipc-toolkit uses
// it: no square roots, and C2 at d = d_hat). The caller scales by the stiffness kappa.

#include <cmath>

#include "solver/kernels/hd.hpp"

namespace grip::solver::kernels {

GRIP_HD inline double barrier(double d, double d_hat) {
  if (d >= d_hat) return 0.0;
  const double t = d - d_hat;
  return -t * t * std::log(d / d_hat);
}

// b'(d) = -2 (d - d_hat) ln(d / d_hat) - (d - d_hat)^2 / d
GRIP_HD inline double barrier_first_derivative(double d, double d_hat) {
  if (d >= d_hat) return 0.0;
  const double t = d - d_hat;
  return -2.0 * t * std::log(d / d_hat) - t * t / d;
}

// b''(d) = -2 ln(d / d_hat) - 4 (d - d_hat) / d + (d - d_hat)^2 / d^2
GRIP_HD inline double barrier_second_derivative(double d, double d_hat) {
  if (d >= d_hat) return 0.0;
  const double t = d - d_hat;
  return -2.0 * std::log(d / d_hat) - 4.0 * t / d + t * t / (d * d);
}

// Magnitude of the contact force kappa * |d b / d(sqrt d)| = -kappa * 2 sqrt(d) b'(d) >= 0 at
// squared distance d: the lagged normal force lambda of IPC's friction.
GRIP_HD inline double barrier_force_magnitude(double d, double d_hat, double kappa) {
  return -2.0 * kappa * std::sqrt(d) * barrier_first_derivative(d, d_hat);
}

}  // namespace grip::solver::kernels
