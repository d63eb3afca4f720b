#pragma once
// The data-parallel Newton iteration's per-environment bookkeeping, as the CPU engine's
// NewtonSolver keeps it for one environment (solver/newton/newton_solver.cpp), with
// prescribed_motion_stages.hpp while prescribed motion is under way:
// - NewtonRightHandSideStage: per DOF, -g, less the force of prescribed motion while it is
//   still to come (prescribed_motion_stages.hpp); 0 at a fixed DOF (pinned, or held by a
//   fixture), whose value the solve takes from FixedMotionStage.
// - FreeResidualStage: per environment, the largest |g| over its free DOFs, the residual its
//   convergence test weighs against newton_tol times its first.
// - StepDisplacementStage: per environment, the largest displacement a step p gives any of its
//   vertices (an FEM vertex's own; an affine body's surface vertex's J(xbar) p), which its
//   other convergence test weighs against newton_velocity_tol h.
// - CommitStage: per DOF, q + alpha p where its environment takes its step; ProgressStage: per
//   environment, how far its prescribed motion has come after it (all the way once a step is
//   taken whole).
#include <Eigen/Core>
#include <cmath>

#include "solver/kernels/affine_body.hpp"
#include "solver/kernels/hd.hpp"
#include "solver/parallel/collision_batch.hpp"
#include "solver/parallel/fem_batch.hpp"
#include "solver/parallel/launch.hpp"

namespace grip::solver::parallel {

struct NewtonRightHandSideStage {
  const char* fixed = nullptr;  // per DOF
  const double* gradient = nullptr;
  const double* kinematic_force = nullptr;  // per DOF; null once prescribed motion is done
  double* rhs = nullptr;

  GRIP_HD void operator()(int d) const {
    const double force = kinematic_force != nullptr ? kinematic_force[d] : 0.0;
    rhs[d] = fixed[d] != 0 ? 0.0 : -gradient[d] - force;
  }
};

struct FreeResidualStage {
  const int* dof_begin = nullptr;  // environments + 1 offsets
  const char* fixed = nullptr;
  const double* gradient = nullptr;
  double* residual = nullptr;  // per environment

  GRIP_HD void operator()(int e) const {
    double largest = 0.0;
    for (int d = dof_begin[e]; d < dof_begin[e + 1]; ++d) {
      const double g = std::abs(gradient[d]);
      if (fixed[d] == 0 && g > largest) largest = g;
    }
    residual[e] = largest;
  }
};

struct StepDisplacementStage {
  VertexBuffers fem_vertices;
  const int* fem_vertex_begin = nullptr;  // environments + 1 offsets
  CollisionVertexBuffers collision;
  const int* collision_vertex_begin = nullptr;  // environments + 1 offsets
  const double* p = nullptr;                    // the batch's step
  double* largest_length = nullptr;             // per environment, m

  GRIP_HD void operator()(int e) const {
    double largest = 0.0;
    for (int v = fem_vertex_begin[e]; v < fem_vertex_begin[e + 1]; ++v) {
      const double length = Eigen::Map<const Eigen::Vector3d>(p + fem_vertices.dof[v]).norm();
      largest = length > largest ? length : largest;
    }
    for (int v = collision_vertex_begin[e]; v < collision_vertex_begin[e + 1]; ++v) {
      if (static_cast<VertexMotion>(collision.motion[v]) != VertexMotion::kAffine) continue;
      const Eigen::Map<const kernels::Vector12d> body(p + collision.dof[v]);
      const Eigen::Vector3d xbar(collision.rest[3 * v], collision.rest[3 * v + 1],
                                 collision.rest[3 * v + 2]);
      const double length = (kernels::affine_body_jacobian(xbar) * body).norm();
      largest = length > largest ? length : largest;
    }
    largest_length[e] = largest;
  }
};

struct CommitStage {
  const int* dof_begin = nullptr;
  int environment_count = 0;
  const unsigned char* take = nullptr;  // per environment: 1 where it takes its step
  const double* alpha = nullptr;        // per environment
  const double* p = nullptr;
  double* q = nullptr;

  GRIP_HD void operator()(int d) const {
    const int e = environment_of(dof_begin, environment_count, d);
    if (take[e] != 0) q[d] += alpha[e] * p[d];
  }
};

struct ProgressStage {
  const unsigned char* take = nullptr;  // per environment
  const double* alpha = nullptr;
  double* progress = nullptr;

  GRIP_HD void operator()(int e) const {
    if (take[e] == 0) return;
    progress[e] = alpha[e] >= 1.0 ? 1.0 : progress[e] + alpha[e] * (1.0 - progress[e]);
  }
};

}  // namespace grip::solver::parallel
