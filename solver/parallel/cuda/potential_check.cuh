#pragma once
// The device check's incremental potential, Newton system and line search (grip-gpu-check,
// potential_check.cu): every environment's energy, gradient, Newton matrix (in 3x3 blocks) and
// force of the prescribed motion still to come (its scripted vertices part way) at one point, and
// Armijo's sufficient decrease along a step whose slope is the energy's own (central differences),
// each environment with its own step, on the device and on one host core. device_check.cu builds
// the scene: its soft box (damped) and affine bodies in one batch, its map scene's collision
// vertices, pairs and lagged friction contacts. The values must agree to round-off, every
// environment's alpha, halvings and outcome exactly.
#include <vector>

#include "solver/parallel/potential_arrays.hpp"

namespace grip::solver::parallel {

struct PotentialScene {
  FemBatch fem;
  AffineBatch affine;
  CollisionBatch collision;
  ContactPairs pairs;
  FrictionContacts friction;
  StepConstants step;
  std::vector<double> q;  // the batch's DOFs where the energies are compared and the search starts
};

struct PotentialCheck {
  double host_ms = 0.0, device_ms = 0.0;  // the energies at q
  double energy = 0.0;                    // their largest relative difference
  double derivatives_host_ms = 0.0, derivatives_device_ms = 0.0;
  // Relative differences: per environment, per block row, per environment; and the matrix's
  // per block, relative to each block's own largest entry (reported, not held to a tolerance).
  double gradient = 0.0, hessian = 0.0, kinematic_force = 0.0, hessian_own_block = 0.0;
  int blocks = 0;  // the Newton matrices' 3x3 blocks
  double decrease_host_ms = 0.0, decrease_device_ms = 0.0;
  int fewest_halvings = 0, most_halvings = 0;  // over environments (host)
  bool decrease_identical = false;             // every environment's alpha, halvings and status
};

PotentialCheck check_potential(const PotentialScene& scene, int repeats);

}  // namespace grip::solver::parallel
