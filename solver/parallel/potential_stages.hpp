#pragma once
// The incremental potential of every environment of a batch at once, as the CPU engine's
// IncrementalPotential::energy gives it:
//   E_e(q) = inertia + h_e^2 (elasticity + damping + orthogonality + drives + barrier + friction)
// Each term's stage writes its items' energies alone, no derivatives (tets, FEM vertices, affine
// bodies, contact pairs, friction contacts), and PotentialSumStage sums each environment's
// items in a fixed order, no atomics: what the line search compares. The sums run in another
// order than the CPU engine's, so the two agree to round-off, not bit for bit.
#include "solver/kernels/hd.hpp"
#include "solver/parallel/affine_batch.hpp"
#include "solver/parallel/affine_stages.hpp"
#include "solver/parallel/collision_batch.hpp"
#include "solver/parallel/contact_stages.hpp"
#include "solver/parallel/elastic_stages.hpp"
#include "solver/parallel/fem_batch.hpp"
#include "solver/parallel/friction_stages.hpp"
#include "solver/parallel/inertia_stages.hpp"
#include "solver/parallel/map_stages.hpp"

namespace grip::solver::parallel {

// What the incremental potential reads besides the DOFs: a step's constants (and a friction
// lag's contacts), each item kind with its environment + 1 offsets.
struct PotentialBuffers {
  int environment_count = 0;
  const double* h = nullptr;         // per environment: the step's length, s
  const double* progress = nullptr;  // per environment: how far scripted vertices have moved
  TetBuffers tets;
  const int* tet_begin = nullptr;
  const double* q_start = nullptr;            // the batch's DOFs at the step's start
  const double* damping_stiffness = nullptr;  // 144 per tet (DampingStage)
  VertexBuffers fem_vertices;
  const int* fem_vertex_begin = nullptr;
  AffineBuffers bodies;
  const int* body_begin = nullptr;
  const double* q_tilde = nullptr;       // the batch's inertia target
  const double* drive_target = nullptr;  // the batch's drive targets
  CollisionVertexBuffers collision;
  const double* scripted_start = nullptr;  // 3 per collision vertex (PositionStage)
  const double* scripted_target = nullptr;
  PairBuffers pairs;  // the barrier's pairs: those within reach on the step's path
  const int* pair_begin = nullptr;
  FrictionBuffers friction;  // the friction lag's contacts
  const int* contact_begin = nullptr;
  const double* start_positions = nullptr;  // 3 per collision vertex, at the step's start
};

// Where the terms' stages write: per item, and the collision vertices' positions.
struct PotentialWork {
  double* x = nullptr;              // 3 per collision vertex
  double* tet = nullptr;            // elasticity and damping
  double* fem_inertia = nullptr;    // per FEM vertex
  double* body_inertia = nullptr;   // per affine body
  double* orthogonality = nullptr;  // per affine body
  double* drive = nullptr;          // per affine body
  double* pair = nullptr;           // barrier
  double* contact = nullptr;        // friction
};

GRIP_HD inline double range_sum(const int* begin, const double* value, int e) {
  double sum = 0.0;
  for (int i = begin[e]; i < begin[e + 1]; ++i) sum += value[i];
  return sum;
}

// Per environment: its items' energies summed, term by term.
struct PotentialSumStage {
  PotentialBuffers b;
  PotentialWork w;
  double* energy = nullptr;  // per environment

  GRIP_HD void operator()(int e) const {
    const double inertia = range_sum(b.fem_vertex_begin, w.fem_inertia, e) +
                           range_sum(b.body_begin, w.body_inertia, e);
    double potential = range_sum(b.tet_begin, w.tet, e);
    potential += range_sum(b.body_begin, w.orthogonality, e);
    potential += range_sum(b.body_begin, w.drive, e);
    potential += range_sum(b.pair_begin, w.pair, e);
    potential += range_sum(b.contact_begin, w.contact, e);
    energy[e] = inertia + b.h[e] * b.h[e] * potential;
  }
};

// Every environment's incremental potential at the batch's DOFs q, into `energy`.
template <class Launcher>
void incremental_potential(Launcher& launch, const PotentialBuffers& b, const double* q,
                           const PotentialWork& w, double* energy) {
  launch(b.collision.count,
         PositionStage{b.collision, q, b.scripted_start, b.scripted_target, b.progress, w.x});
  launch(b.tets.count, ElasticStage{b.tets, q, true, w.tet, nullptr, nullptr});
  launch(b.tets.count,
         DampingStage{b.tets, q, b.q_start, b.damping_stiffness, b.h, w.tet, nullptr, nullptr});
  launch(b.fem_vertices.count, InertiaStage{b.fem_vertices, q, b.q_tilde, w.fem_inertia, nullptr});
  launch(b.bodies.count, AffineInertiaStage{b.bodies, q, b.q_tilde, w.body_inertia, nullptr});
  launch(b.bodies.count, OrthogonalityStage{b.bodies, q, true, w.orthogonality, nullptr, nullptr});
  launch(b.bodies.count, DriveStage{b.bodies, q, b.drive_target, w.drive, nullptr});
  launch(b.pairs.count, BarrierStage{b.pairs, w.x, nullptr, w.pair, nullptr, nullptr});
  launch(b.friction.count,
         FrictionStage{b.friction, w.x, b.start_positions, w.contact, nullptr, nullptr});
  launch(b.environment_count, PotentialSumStage{b, w, energy});
}

// The work arrays of `b`'s batch in host (HostArray) or device (DeviceArray) memory.
template <template <class> class Array>
struct PotentialStorage {
  explicit PotentialStorage(const PotentialBuffers& b)
      : x(3 * std::size_t(b.collision.count)),
        tet(std::size_t(b.tets.count)),
        fem_inertia(std::size_t(b.fem_vertices.count)),
        body_inertia(std::size_t(b.bodies.count)),
        orthogonality(std::size_t(b.bodies.count)),
        drive(std::size_t(b.bodies.count)),
        pair(std::size_t(b.pairs.count)),
        contact(std::size_t(b.friction.count)) {}

  PotentialWork work() {
    return {
        x.data(),     tet.data(),  fem_inertia.data(), body_inertia.data(), orthogonality.data(),
        drive.data(), pair.data(), contact.data()};
  }

  Array<double> x, tet, fem_inertia, body_inertia, orthogonality, drive, pair, contact;
};

}  // namespace grip::solver::parallel
