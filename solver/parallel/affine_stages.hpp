#pragma once
// The data-parallel engine's stages for affine bodies, one source for every launcher
// (launch.hpp), as the CPU engine's AffineBodies and DrivenBodies compute them, one item per
// body of a batch (affine_batch.hpp):
// - AffinePredictionStage: the inertia target q~ = q + h v + h^2 M^-1 f_g at a step's start
//   (f_g the body's weight; none on a driven body). Per environment: its h and gravity.
// - AffineInertiaStage: 1/2 (q - q~)^T M (q - q~) and its gradient M (q - q~).
// - OrthogonalityStage: ABD's kappa V |A A^T - I|_F^2, its gradient, and its Hessian's 9x9
//   block in the rows of A, PSD-projected by Jacobi rotations (kernels/jacobi_psd_projection.hpp;
//   the CPU engine's Eigen eigen-solver is host-only).
// - DriveStage: a driven body's spring towards its drive target, k / m 1/2 (q - t)^T M (q - t),
//   and its gradient.
// Energies are written per body (EnvironmentSumStage sums them per environment); gradients are
// added into the batch's gradient at the body's own 12 DOFs, which no other item touches. The
// inertia and drive Hessians are M and (k / m) M: the assembly reads the mass matrices.
// Products are written as loops over the column-major 12x12 matrices, so that device code
// needs no Eigen product kernel; they agree with the CPU engine's Eigen products to round-off.
#include <Eigen/Core>

#include "solver/kernels/affine_body.hpp"
#include "solver/kernels/hd.hpp"
#include "solver/kernels/jacobi_psd_projection.hpp"
#include "solver/parallel/affine_batch.hpp"

namespace grip::solver::parallel {

// y = M x for a 12x12 column-major M, summed over columns in order.
GRIP_HD inline void multiply_12(const double* m, const double* x, double* y) {
  for (int r = 0; r < 12; ++r) y[r] = 0.0;
  for (int c = 0; c < 12; ++c) {
    for (int r = 0; r < 12; ++r) y[r] += m[12 * c + r] * x[c];
  }
}

struct AffinePredictionStage {
  AffineBuffers bodies;
  const double* q = nullptr;        // the batch's DOFs at the step's start
  const double* v = nullptr;        // and velocities
  const double* h = nullptr;        // per environment
  const double* gravity = nullptr;  // 3 per environment
  double* q_tilde = nullptr;        // the batch's inertia target (written at the body's DOFs)

  GRIP_HD void operator()(int i) const {
    const int dof = bodies.dof[i], e = bodies.environment[i];
    const double step = h[e];
    // The weight as a generalized force acts on p alone: J(0)^T m g = (m g, 0, ..., 0).
    double force[12] = {};
    for (int k = 0; k < 3; ++k) force[k] = bodies.weight_mass[i] * gravity[3 * e + k];
    double fall[12];
    multiply_12(bodies.mass_matrix_inverse + 144 * i, force, fall);
    for (int k = 0; k < 12; ++k) {
      q_tilde[dof + k] = q[dof + k] + step * v[dof + k] + step * step * fall[k];
    }
  }
};

struct AffineInertiaStage {
  AffineBuffers bodies;
  const double* q = nullptr;
  const double* q_tilde = nullptr;
  double* energy = nullptr;    // per body
  double* gradient = nullptr;  // the batch's gradient: the body's share is added; null: none

  GRIP_HD void operator()(int i) const {
    const int dof = bodies.dof[i];
    double dq[12], m_dq[12];
    for (int k = 0; k < 12; ++k) dq[k] = q[dof + k] - q_tilde[dof + k];
    multiply_12(bodies.mass_matrix + 144 * i, dq, m_dq);
    double squared = 0.0;
    for (int k = 0; k < 12; ++k) {
      squared += dq[k] * m_dq[k];
      if (gradient != nullptr) gradient[dof + k] += m_dq[k];
    }
    energy[i] = 0.5 * squared;
  }
};

struct OrthogonalityStage {
  AffineBuffers bodies;
  const double* q = nullptr;
  bool project = true;         // PSD-project the Hessian (projected Newton)
  double* energy = nullptr;    // per body
  double* gradient = nullptr;  // the batch's gradient: the body's share is added; null: none
  double* hessian = nullptr;   // 81 per body: the 9x9 block in (a1, a2, a3), column-major; null:
                               // not wanted

  GRIP_HD void operator()(int i) const {
    const int dof = bodies.dof[i];
    kernels::Vector12d qb;
    for (int k = 0; k < 12; ++k) qb[k] = q[dof + k];
    const double stiffness = bodies.orthogonality_stiffness[i], volume = bodies.volume[i];
    energy[i] = kernels::affine_body_orthogonality_energy(qb, stiffness, volume);
    if (gradient == nullptr) return;
    const kernels::Vector12d g = kernels::affine_body_orthogonality_gradient(qb, stiffness, volume);
    for (int k = 0; k < 12; ++k) gradient[dof + k] += g[k];
    if (!hessian) return;
    Eigen::Matrix<double, 9, 9> block =
        kernels::affine_body_orthogonality_block(qb, stiffness, volume);
    if (project) block = kernels::project_to_psd_jacobi<9>(block);
    Eigen::Map<Eigen::Matrix<double, 9, 9>>(hessian + 81 * i) = block;
  }
};

struct DriveStage {
  AffineBuffers bodies;
  const double* q = nullptr;
  const double* target = nullptr;  // the batch's drive targets (read at driven bodies' DOFs)
  double* energy = nullptr;        // per body (0 where not driven)
  double* gradient = nullptr;      // the batch's gradient: a driven body's share is added (null:
                                   // none)

  GRIP_HD void operator()(int i) const {
    const double k = bodies.drive_stiffness[i];
    energy[i] = 0.0;
    if (k == 0.0) return;
    const int dof = bodies.dof[i];
    const double* m = bodies.mass_matrix + 144 * i;
    const double s = k / m[0];  // k / the body's mass
    double dq[12], m_dq[12];
    for (int c = 0; c < 12; ++c) dq[c] = q[dof + c] - target[dof + c];
    multiply_12(m, dq, m_dq);
    double squared = 0.0;
    for (int c = 0; c < 12; ++c) {
      squared += dq[c] * m_dq[c];
      if (gradient != nullptr) gradient[dof + c] += s * m_dq[c];
    }
    energy[i] = 0.5 * s * squared;
  }
};

}  // namespace grip::solver::parallel
