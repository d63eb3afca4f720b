#pragma once
// The data-parallel engine's flat buffers from the models of a batch's environments, in
// environment order; each environment's DOFs laid out as the CPU engine lays them (Model's body
// order), so that the two engines' states are the same vectors.
#include <vector>

#include "solver/model/model.hpp"
#include "solver/parallel/affine_batch.hpp"
#include "solver/parallel/collision_batch.hpp"
#include "solver/parallel/fem_batch.hpp"
#include "solver/parallel/surface_batch.hpp"

namespace grip::solver::parallel {

// Every deforming body's tets of every environment (one model per environment; models may
// repeat).
FemBatch fem_batch(const std::vector<const Model*>& environments);

// Every affine and driven body of every environment, with the values the CPU engine's
// AffineBodies and DrivenBodies hold.
AffineBatch affine_batch(const std::vector<const Model*>& environments);

// Every collision vertex of every environment, in the model's collision order
// (CollisionMesh), with the DOFs it moves with.
CollisionBatch collision_batch(const std::vector<const Model*>& environments);

// Per DOF of the batch, 1 where a pin prescribes it (Model::prescribed): the DOFs whose motion
// FixedMotionStage gives the solve.
std::vector<char> prescribed_dofs(const std::vector<const Model*>& environments);

// Every collision surface of every environment (CollisionMesh): vertices, edges, faces, which
// bodies may touch, and each body's own pairs near at rest.
SurfaceBatch surface_batch(const std::vector<const Model*>& environments);

}  // namespace grip::solver::parallel
