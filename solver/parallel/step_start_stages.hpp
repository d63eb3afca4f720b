#pragma once
// The constants a step takes from the state at its start (StepConstants), computed by the
// stages where the state is, as the CPU engine's NewtonSolver::begin_step and
// IncrementalPotential::begin_step compute them for one environment:
// - the inertia target q_tilde = q + h v + h^2 M^-1 f_gravity (PredictionStage for FEM
//   vertices, AffinePredictionStage for affine bodies);
// - the damping's stiffness, each tet's projected elastic Hessian at q (ElasticStage);
// - the collision vertices' positions at the start (PositionStage at progress 0: scripted
//   vertices where their scripts begin the step).
// What comes from scripts (drive targets, scripted vertices' start and end, pinned vertices'
// targets) the host gives. fill_step_start_constants does the same on the host, for a
// StepConstants built there.
#include <vector>

#include "solver/parallel/affine_stages.hpp"
#include "solver/parallel/elastic_stages.hpp"
#include "solver/parallel/inertia_stages.hpp"
#include "solver/parallel/launch.hpp"
#include "solver/parallel/map_stages.hpp"
#include "solver/parallel/potential_arrays.hpp"
#include "solver/parallel/potential_stages.hpp"

namespace grip::solver::parallel {

// Where the constants are written, and the work they need.
struct StepStartOutput {
  double* q_tilde = nullptr;            // the batch's DOFs
  double* damping_stiffness = nullptr;  // 144 per tet
  double* start_positions = nullptr;    // 3 per collision vertex
  double* tet_energy = nullptr;         // work: per tet
  double* tet_gradient = nullptr;       // work: 12 per tet
};

// From the batch's DOFs b.q_start, velocities `v` and gravity (3 per environment), with each
// environment's b.h; b.progress must be 0 (the step's start).
template <class Launcher>
void step_start_constants(Launcher& launch, const PotentialBuffers& b, const double* v,
                          const double* gravity, const StepStartOutput& out) {
  launch(b.fem_vertices.count,
         PredictionStage{b.fem_vertices, b.q_start, v, b.h, gravity, out.q_tilde});
  launch(b.bodies.count, AffinePredictionStage{b.bodies, b.q_start, v, b.h, gravity, out.q_tilde});
  launch(b.tets.count, ElasticStage{b.tets, b.q_start, true, out.tet_energy, out.tet_gradient,
                                    out.damping_stiffness});
  launch(b.collision.count, PositionStage{b.collision, b.q_start, b.scripted_start,
                                          b.scripted_target, b.progress, out.start_positions});
}

// step_start_constants on one host core into `k`, whose h, q_start and scripted start and
// target are set (its progress is 0 while it runs, then as it was).
void fill_step_start_constants(StepConstants& k, const FemBatch& fem, const AffineBatch& affine,
                               const CollisionBatch& collision, const std::vector<double>& v,
                               const std::vector<double>& gravity);

}  // namespace grip::solver::parallel
