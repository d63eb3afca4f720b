#pragma once
// The data-parallel Newton system while prescribed motion is still to come, as the CPU engine's
// NewtonSolver builds it for one environment (assemble and eliminate_prescribed in
// solver/newton/newton_solver.cpp): a step that begins with scripted bodies and pinned vertices
// short of their targets (progress < 1, after CCD stopped them at a contact) asks Newton to make
// room for them before they arrive.
// - KinematicMotionStage: per collision vertex, the motion still to come, x at progress 1 less
//   x at its environment's progress: a scripted vertex's rest of its way, 0 for any other.
// - KinematicForceStage: per contact (barrier pairs, then friction contacts), the force
//   H_c dk_c (12 values) that its h^2-scaled Hessian gives the motion of its four vertices;
//   gathered into the DOFs by J^T like a gradient (ContactGatherStage), H_fk dk of the CPU
//   engine's Stencil::add_kinematic_force.
// - FixedMotionStage: per DOF, the value the linear solve keeps at a fixed DOF: a pinned DOF's
//   motion still to come (its target less q) while its environment's progress is short of 1,
//   else 0 (a held DOF stays, and a pinned one that has arrived moves no further). The solve
//   (block_pcg.hpp) subtracts the fixed DOFs' share A_fc x_c from the free rows, the elimination's
//   lift.
#include "solver/kernels/hd.hpp"
#include "solver/parallel/collision_batch.hpp"
#include "solver/parallel/derivative_stages.hpp"
#include "solver/parallel/launch.hpp"
#include "solver/parallel/map_stages.hpp"
#include "solver/parallel/potential_stages.hpp"

namespace grip::solver::parallel {

struct KinematicMotionStage {
  CollisionVertexBuffers vertices;
  const double* scripted_target = nullptr;  // 3 per collision vertex
  const double* x = nullptr;                // 3 per collision vertex, at the progress so far
  double* motion = nullptr;                 // 3 per collision vertex

  GRIP_HD void operator()(int v) const {
    const bool scripted = static_cast<VertexMotion>(vertices.motion[v]) == VertexMotion::kScripted;
    for (int k = 0; k < 3; ++k) {
      motion[3 * v + k] = scripted ? scripted_target[3 * v + k] - x[3 * v + k] : 0.0;
    }
  }
};

struct KinematicForceStage {
  const int* contact_vertex = nullptr;  // 4 per contact
  const double* hessian = nullptr;      // 144 per contact, scaled by h^2, column-major
  const double* motion = nullptr;       // 3 per collision vertex
  double* force = nullptr;              // 12 per contact

  GRIP_HD void operator()(int c) const {
    double dk[12];
    for (int i = 0; i < 4; ++i) {
      for (int k = 0; k < 3; ++k) dk[3 * i + k] = motion[3 * contact_vertex[4 * c + i] + k];
    }
    const double* h = hessian + 144 * c;
    for (int r = 0; r < 12; ++r) {
      double sum = 0.0;
      for (int k = 0; k < 12; ++k) sum += h[12 * k + r] * dk[k];
      force[12 * c + r] = sum;
    }
  }
};

// The batch's force of prescribed motion (its DOFs) from the contacts' Hessians that
// incremental_potential_derivatives left in `dw` at positions `w.x`: `motion` 3 per collision
// vertex and `contact_force` 12 per contact are work arrays.
template <class Launcher>
void kinematic_force(Launcher& launch, const PotentialBuffers& b, const DerivativeBuffers& d,
                     const PotentialWork& w, const DerivativeWork& dw, double* motion,
                     double* contact_force, double* force) {
  const int contacts = b.pairs.count + b.friction.count;
  const double* contact_hessian =
      dw.stencil_hessian + 144 * (std::size_t(b.tets.count) + std::size_t(b.bodies.count));
  launch(b.collision.count, KinematicMotionStage{b.collision, b.scripted_target, w.x, motion});
  launch(contacts, KinematicForceStage{d.contact_vertex, contact_hessian, motion, contact_force});
  launch(d.dof_count, ZeroStage{force});
  launch(d.contact_incidence.count, ContactGatherStage{d.contact_incidence, d.contact_vertex,
                                                       b.collision.rest, contact_force, force});
}

struct FixedMotionStage {
  const int* dof_begin = nullptr;  // environments + 1 offsets
  int environment_count = 0;
  const double* progress = nullptr;           // per environment
  const char* prescribed = nullptr;           // per DOF: 1 where a pin prescribes it
  const double* prescribed_target = nullptr;  // per DOF (read where prescribed)
  const double* q = nullptr;
  double* x = nullptr;  // per DOF: the solve's fixed values (free DOFs' first guess 0)

  GRIP_HD void operator()(int d) const {
    const int e = environment_of(dof_begin, environment_count, d);
    x[d] = prescribed[d] != 0 && progress[e] < 1.0 ? prescribed_target[d] - q[d] : 0.0;
  }
};

}  // namespace grip::solver::parallel
