#pragma once
// The data-parallel engine's map between DOFs and collision vertices, one source for every
// launcher (launch.hpp), as the CPU engine's collision_positions and Stencil do it:
// - PositionStage: each collision vertex's position from the batch's DOFs: an FEM vertex's own,
//   A xbar + p for an affine body's (kernels/affine_body.hpp), and for a scripted vertex
//   (`progress` of the way from its start to its target, per environment: CCD stops prescribed
//   motion short of a contact and Newton goes on from there) what the host gave for the step.
// - ContactGatherStage: per DOF block, the contact pairs' position-space gradients (12 per
//   pair, from the barrier and friction stages) of the slots that touch it, mapped to its DOFs
//   by J^T (the identity for an FEM vertex, J(xbar)^T for an affine body) and summed in slot
//   order, no atomics. Scripted vertices have no DOFs: their slots are in no block.
#include <Eigen/Core>

#include "solver/kernels/affine_body.hpp"
#include "solver/kernels/hd.hpp"
#include "solver/parallel/collision_batch.hpp"

namespace grip::solver::parallel {

struct PositionStage {
  CollisionVertexBuffers vertices;
  const double* q = nullptr;                // the batch's DOFs
  const double* scripted_start = nullptr;   // 3 per vertex (read at scripted vertices)
  const double* scripted_target = nullptr;  // 3 per vertex
  const double* progress = nullptr;         // per environment, in [0, 1]
  double* x = nullptr;                      // 3 per vertex

  GRIP_HD void operator()(int v) const {
    const int dof = vertices.dof[v];
    switch (static_cast<VertexMotion>(vertices.motion[v])) {
      case VertexMotion::kFem:
        for (int k = 0; k < 3; ++k) x[3 * v + k] = q[dof + k];
        break;
      case VertexMotion::kAffine: {
        kernels::Vector12d body;
        for (int k = 0; k < 12; ++k) body[k] = q[dof + k];
        const Eigen::Vector3d rest(vertices.rest[3 * v], vertices.rest[3 * v + 1],
                                   vertices.rest[3 * v + 2]);
        const Eigen::Vector3d p = kernels::affine_body_position(body, rest);
        for (int k = 0; k < 3; ++k) x[3 * v + k] = p[k];
        break;
      }
      case VertexMotion::kScripted: {
        const double t = progress[vertices.environment[v]];
        for (int k = 0; k < 3; ++k) {
          x[3 * v + k] = (1.0 - t) * scripted_start[3 * v + k] + t * scripted_target[3 * v + k];
        }
        break;
      }
    }
  }
};

struct ContactGatherStage {
  ContactIncidenceBuffers incidence;
  const int* pair_vertex = nullptr;       // 4 per pair: collision vertices of the batch
  const double* rest = nullptr;           // 3 per collision vertex (CollisionVertexBuffers::rest)
  const double* pair_gradient = nullptr;  // 12 per pair, position space
  double* gradient = nullptr;  // the batch's DOF-space gradient: each block's sum is added

  GRIP_HD void operator()(int b) const {
    double sum[12] = {};
    const bool affine = incidence.block_size[b] == 12;
    for (int s = incidence.begin[b]; s < incidence.begin[b + 1]; ++s) {
      const int slot = incidence.slots[s];
      const double* g = pair_gradient + 3 * slot;  // the slot's 3 of its pair's 12
      for (int k = 0; k < 3; ++k) sum[k] += g[k];
      if (!affine) continue;
      // J(xbar)^T g: the rows a_i of A take g_i xbar.
      const double* xbar = rest + 3 * pair_vertex[slot];
      for (int i = 0; i < 3; ++i) {
        for (int k = 0; k < 3; ++k) sum[3 + 3 * i + k] += g[i] * xbar[k];
      }
    }
    const int dof = incidence.block_dof[b];
    for (int k = 0; k < incidence.block_size[b]; ++k) gradient[dof + k] += sum[k];
  }
};

}  // namespace grip::solver::parallel
