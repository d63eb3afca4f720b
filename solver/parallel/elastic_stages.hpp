#pragma once
// The data-parallel engine's elastic stages, one source for every launcher (launch.hpp): per
// tet, the stable Neo-Hookean energy, its 12-vector gradient and 12x12 Hessian (PSD-projected by
// the analytic eigensystem, as the CPU engine's FemBodies does), from the same GRIP_HD kernels;
// then, per FEM vertex, its gradient gathered from its tets' slots, and per environment, its
// energy summed over its tets, each in a fixed order.
#include <Eigen/Core>

#include "solver/kernels/hd.hpp"
#include "solver/kernels/neo_hookean.hpp"
#include "solver/parallel/fem_batch.hpp"

namespace grip::solver::parallel {

struct ElasticStage {
  TetBuffers tets;
  const double* q = nullptr;   // the batch's DOFs
  bool project = true;         // PSD-project the Hessian (projected Newton)
  double* energy = nullptr;    // per tet
  double* gradient = nullptr;  // 12 per tet; null: the energy alone (a line search's)
  double* hessian = nullptr;   // 144 per tet, column-major; null: not wanted

  GRIP_HD void operator()(int t) const {
    kernels::Vector12d x;
    for (int c = 0; c < 4; ++c) {
      const int dof = tets.dofs[4 * t + c];
      for (int k = 0; k < 3; ++k) x[3 * c + k] = q[dof + k];
    }
    const Eigen::Map<const Eigen::Matrix3d> dm_inverse(tets.rest_shape_inverse + 9 * t);
    const Eigen::Matrix3d rest_shape_inverse = dm_inverse;
    const double volume = tets.rest_volume[t];
    const kernels::StableNeoHookeanParameters m{tets.mu[t], tets.lambda[t]};
    const Eigen::Matrix3d f = kernels::deformation_gradient(x, rest_shape_inverse);
    energy[t] = volume * kernels::stable_neo_hookean_energy_density(f, m);
    if (gradient == nullptr) return;
    Eigen::Map<kernels::Vector12d> g(gradient + 12 * t);
    g = kernels::tet_stable_neo_hookean_gradient(f, rest_shape_inverse, volume, m);
    if (hessian == nullptr) return;
    Eigen::Map<kernels::Matrix12d> h(hessian + 144 * t);
    h = kernels::tet_stable_neo_hookean_hessian(f, rest_shape_inverse, volume, m, project);
  }
};

// Rayleigh damping, added to each damped tet's elastic values (after ElasticStage), as the CPU
// engine's FemBodies adds it: beta / (2 h) dx^T K dx with dx the tet's motion since the step's
// start and K its projected elastic Hessian there (ElasticStage's, at the step's start), so
// a convex quadratic within the step; the gradient gains beta / h K dx, the Hessian beta / h K.
struct DampingStage {
  TetBuffers tets;
  const double* q = nullptr;          // the batch's DOFs
  const double* q_start = nullptr;    // and at the step's start
  const double* stiffness = nullptr;  // 144 per tet: K, column-major
  const double* h = nullptr;          // per environment
  double* energy = nullptr;           // per tet: the damping is added
  double* gradient = nullptr;         // 12 per tet: added; null: the energy alone
  double* hessian = nullptr;          // 144 per tet: added; null: not wanted

  GRIP_HD void operator()(int t) const {
    const double beta = tets.damping[t];
    if (beta == 0.0) return;
    const double c = beta / h[tets.environment[t]];
    kernels::Vector12d dx;
    for (int v = 0; v < 4; ++v) {
      const int dof = tets.dofs[4 * t + v];
      for (int k = 0; k < 3; ++k) dx[3 * v + k] = q[dof + k] - q_start[dof + k];
    }
    const Eigen::Map<const kernels::Matrix12d> k(stiffness + 144 * t);
    const kernels::Vector12d k_dx = k * dx;
    energy[t] += 0.5 * c * dx.dot(k_dx);
    if (gradient == nullptr) return;
    Eigen::Map<kernels::Vector12d>(gradient + 12 * t) += c * k_dx;
    if (hessian == nullptr) return;
    Eigen::Map<kernels::Matrix12d>(hessian + 144 * t) += c * k;
  }
};

// Per FEM vertex: the sum of its tets' gradient 3-vectors, in slot order, into the batch's
// DOF-space gradient (which it overwrites at the vertex's DOFs).
struct GradientGatherStage {
  IncidenceBuffers incidence;
  const double* tet_gradient = nullptr;  // 12 per tet (ElasticStage::gradient)
  double* gradient = nullptr;            // the batch's DOF-space gradient

  GRIP_HD void operator()(int v) const {
    double sum[3] = {0.0, 0.0, 0.0};
    for (int s = incidence.begin[v]; s < incidence.begin[v + 1]; ++s) {
      const int slot = incidence.slots[s];  // 4 t + c: corner c of tet t
      for (int k = 0; k < 3; ++k) sum[k] += tet_gradient[3 * slot + k];
    }
    for (int k = 0; k < 3; ++k) gradient[incidence.vertex_dof[v] + k] = sum[k];
  }
};

// Per environment: its tets' energies summed in tet order.
struct EnvironmentSumStage {
  const int* tet_begin = nullptr;  // environment_count + 1 offsets
  const double* tet_energy = nullptr;
  double* energy = nullptr;  // per environment

  GRIP_HD void operator()(int e) const {
    double sum = 0.0;
    for (int t = tet_begin[e]; t < tet_begin[e + 1]; ++t) sum += tet_energy[t];
    energy[e] = sum;
  }
};

// Where one elastic pass writes: per tet, the batch's gradient, per environment.
struct ElasticOutputs {
  double* tet_energy = nullptr;
  double* tet_gradient = nullptr;        // 12 per tet
  double* hessian = nullptr;             // 144 per tet, projected; null: not wanted
  double* gradient = nullptr;            // the batch's DOF-space gradient (FEM DOFs written)
  double* environment_energy = nullptr;  // per environment
};

// The elastic stages in the order a Newton iteration needs them: every tet, then the gather
// into the vertices, then the environments' sums. `tet_begin` holds environments + 1 offsets.
template <class Launcher>
void launch_elastic_stages(Launcher&& launch, const TetBuffers& tets,
                           const IncidenceBuffers& incidence, const int* tet_begin,
                           int environments, const double* q, const ElasticOutputs& out) {
  launch(tets.count, ElasticStage{tets, q, true, out.tet_energy, out.tet_gradient, out.hessian});
  launch(incidence.count, GradientGatherStage{incidence, out.tet_gradient, out.gradient});
  launch(environments, EnvironmentSumStage{tet_begin, out.tet_energy, out.environment_energy});
}

}  // namespace grip::solver::parallel
