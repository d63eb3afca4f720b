#pragma once
// The data-parallel engine's inertia stages for FEM vertices, one source for every launcher
// (launch.hpp), as the CPU engine's FemBodies computes them: the inertia target
// q~ = q + h v + h^2 g of each vertex at a step's start, and the inertia term
// 1/2 m |q - q~|^2, its gradient m (q - q~) (added into the batch's gradient) and its diagonal
// Hessian m. Per environment: its step h and its gravity g.
#include "solver/kernels/hd.hpp"
#include "solver/parallel/fem_batch.hpp"

namespace grip::solver::parallel {

struct PredictionStage {
  VertexBuffers vertices;
  const double* q = nullptr;        // the batch's DOFs at the step's start
  const double* v = nullptr;        // and velocities
  const double* h = nullptr;        // per environment
  const double* gravity = nullptr;  // 3 per environment
  double* q_tilde = nullptr;        // the batch's inertia target (written at FEM DOFs)

  GRIP_HD void operator()(int i) const {
    const int dof = vertices.dof[i], e = vertices.environment[i];
    const double step = h[e];
    for (int k = 0; k < 3; ++k) {
      const double predicted = q[dof + k] + step * v[dof + k];
      q_tilde[dof + k] = predicted + step * step * gravity[3 * e + k];
    }
  }
};

struct InertiaStage {
  VertexBuffers vertices;
  const double* q = nullptr;
  const double* q_tilde = nullptr;
  double* energy = nullptr;    // per vertex
  double* gradient = nullptr;  // the batch's gradient: the vertex's share is added; null: none

  GRIP_HD void operator()(int i) const {
    const int dof = vertices.dof[i];
    const double m = vertices.mass[i];
    double squared = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double dx = q[dof + k] - q_tilde[dof + k];
      squared += dx * dx;
      if (gradient != nullptr) gradient[dof + k] += m * dx;
    }
    energy[i] = 0.5 * m * squared;
  }
};

}  // namespace grip::solver::parallel
