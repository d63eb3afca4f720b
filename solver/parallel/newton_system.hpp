#pragma once
// A batch's Newton system assembled on the host launchers over host arrays: every
// environment's gradient and matrix blocks (derivative_stages.hpp), the force of the prescribed
// motion still to come (prescribed_motion_stages.hpp), the collision vertices' positions at q,
// and the derivative structure the blocks were assembled on. What newton_iteration.hpp solves,
// and what the tests compare with the CPU engine's.
#include <vector>

#include "solver/parallel/affine_batch.hpp"
#include "solver/parallel/collision_batch.hpp"
#include "solver/parallel/contact_stages.hpp"
#include "solver/parallel/derivative_stages.hpp"
#include "solver/parallel/fem_batch.hpp"
#include "solver/parallel/friction_stages.hpp"
#include "solver/parallel/potential_arrays.hpp"
#include "solver/parallel/prescribed_motion_stages.hpp"

namespace grip::solver::parallel {

struct NewtonSystem {
  std::vector<double> gradient, blocks, force;  // the batch's DOFs; 9 per block; the DOFs
  std::vector<double> x;                        // 3 per collision vertex
  DerivativeStructure structure;
};

// At q, with the barrier over `pairs`, the friction lag's `friction` and the step's constants;
// the contacts' Hessians left exact where `exact` says 1 (per environment; null: projected
// everywhere).
template <class Launcher>
NewtonSystem newton_system(Launcher&& launch, const FemBatch& fem, const AffineBatch& affine,
                           const CollisionBatch& collision, const ContactPairs& pairs,
                           const FrictionContacts& friction, const StepConstants& step,
                           const std::vector<double>& q, const unsigned char* exact = nullptr) {
  const PotentialArrays<HostArray> arrays(fem, affine, collision, pairs, friction, step);
  const PotentialBuffers b = arrays.buffers();
  PotentialStorage<HostArray> work(b);
  NewtonSystem s;
  s.structure = derivative_structure(fem, affine, collision, pairs, friction);
  DerivativeStorage<HostArray> storage(s.structure, fem, affine, collision);
  s.gradient.resize(q.size());
  s.force.resize(q.size());
  s.blocks.resize(9 * s.structure.pattern.row.size());
  incremental_potential_derivatives(launch, b, storage.buffers(), q.data(), work.work(),
                                    storage.work(), exact, s.gradient.data(), s.blocks.data());
  std::vector<double> motion(work.x.size()), contact_force(3 * s.structure.contact_vertex.size());
  kinematic_force(launch, b, storage.buffers(), work.work(), storage.work(), motion.data(),
                  contact_force.data(), s.force.data());
  s.x = work.x;
  return s;
}

}  // namespace grip::solver::parallel
