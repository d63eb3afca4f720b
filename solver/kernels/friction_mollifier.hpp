#pragma once
// IPC's smoothed static-to-dynamic friction transition. f1(y) replaces the sign of the sliding
// speed y >= 0: it rises from 0 to 1 over [0, eps] (eps = eps_v for velocities, eps_v * dt for
// displacements per step) and f0 is its antiderivative with f0(eps) = eps.

#include "solver/kernels/hd.hpp"

namespace grip::solver::kernels {

// f0(y) = -y^3 / (3 eps^2) + y^2 / eps + eps / 3 for y < eps, else y.
GRIP_HD inline double friction_f0(double y, double eps) {
  if (y >= eps) return y;
  return y * y * (-y / (3.0 * eps * eps) + 1.0 / eps) + eps / 3.0;
}

// f1(y) = f0'(y) = -y^2 / eps^2 + 2 y / eps for y < eps, else 1.
GRIP_HD inline double friction_f1(double y, double eps) {
  if (y >= eps) return 1.0;
  return y * (2.0 / eps - y / (eps * eps));
}

// f1(y) / y = -y / eps^2 + 2 / eps for y < eps, else 1 / y: finite at y = 0 (2 / eps).
GRIP_HD inline double friction_f1_over_y(double y, double eps) {
  if (y >= eps) return 1.0 / y;
  return 2.0 / eps - y / (eps * eps);
}

// d/dy (f1(y) / y) = -1 / eps^2 for y < eps, else -1 / y^2 (continuous at eps).
GRIP_HD inline double friction_f1_over_y_derivative(double y, double eps) {
  if (y >= eps) return -1.0 / (y * y);
  return -1.0 / (eps * eps);
}

}  // namespace grip::solver::kernels
