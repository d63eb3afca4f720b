#pragma once
// The incremental potential's gradient and Hessian in every environment's DOFs at once, as the
// CPU engine's IncrementalPotential::derivatives gives them: the Newton system of a batch.
//   g = inertia's + h^2 (elasticity's + damping's + orthogonality's + drives' + barrier's +
//       friction's)
//   H = M + h^2 (...), the Hessians PSD-projected per element (projected Newton)
// Per item the terms' stages write their gradients and Hessians (tets, affine bodies, contact
// pairs and friction contacts, the last two in one list of contacts); the h^2 terms' gradients
// are gathered into one DOF vector, scaled by each environment's h^2 and added to the inertia's
// (CombineGradientStage), and their Hessians scaled per item before the blocks are assembled
// (block_assembly.hpp), so that every sum runs in a fixed order, no atomics. The sums run in
// another order than the CPU engine's: the two agree to round-off.
#include <vector>

#include "solver/kernels/hd.hpp"
#include "solver/parallel/block_assembly.hpp"
#include "solver/parallel/collision_batch.hpp"
#include "solver/parallel/launch.hpp"
#include "solver/parallel/potential_stages.hpp"

namespace grip::solver::parallel {

// What the derivatives read besides PotentialBuffers: how items map to DOFs and blocks. Built
// on the host whenever the contacts change (DerivativeStructure).
struct DerivativeBuffers {
  const int* dof_begin = nullptr;  // environments + 1 offsets into the batch's DOFs
  int dof_count = 0;
  // The FEM vertices' tet slots (FemBatch::incidence: FEM vertices + 1 offsets, the slots); the
  // vertices' DOFs are PotentialBuffers::fem_vertices'.
  const int* fem_incidence_begin = nullptr;
  const int* fem_incidence_slots = nullptr;
  ContactIncidenceBuffers contact_incidence;  // DOF blocks' contact slots
  const int* contact_vertex = nullptr;        // 4 per contact: the pairs', then the friction's
  BlockPatternBuffers pattern;
  const double* slot_rest = nullptr;  // 3 per stencil slot (StencilSlots::rest)
  const int* diagonal = nullptr;      // per FEM vertex: its diagonal block
};

// Where the derivatives write besides PotentialWork (whose energies and positions they fill).
struct DerivativeWork {
  double* tet_gradient = nullptr;        // 12 per tet
  double* contact_gradient = nullptr;    // 12 per contact: pairs, then friction contacts
  double* stencil_hessian = nullptr;     // 144 per stencil: tets, bodies, pairs, friction
  double* orthogonality = nullptr;       // 81 per affine body
  double* potential_gradient = nullptr;  // the batch's DOFs: the h^2 terms' gradient
};

// Per item: its `stride` values times its environment's h^2.
struct StepSquaredScaleStage {
  const int* environment = nullptr;  // per item
  const double* h = nullptr;         // per environment
  double* values = nullptr;
  int stride = 0;

  GRIP_HD void operator()(int i) const {
    const double step = h[environment[i]], scale = step * step;
    for (int k = 0; k < stride; ++k) values[stride * i + k] *= scale;
  }
};

struct ZeroStage {
  double* values = nullptr;
  GRIP_HD void operator()(int i) const { values[i] = 0.0; }
};

// Per DOF: the inertia's gradient plus h^2 times the other terms'.
struct CombineGradientStage {
  const int* dof_begin = nullptr;
  int environment_count = 0;
  const double* h = nullptr;
  const double* potential_gradient = nullptr;
  double* gradient = nullptr;

  GRIP_HD void operator()(int d) const {
    const double step = h[environment_of(dof_begin, environment_count, d)];
    gradient[d] += step * step * potential_gradient[d];
  }
};

// The h^2 terms' per-item derivatives at q, scaled by h^2 where they go into the Hessian.
template <class Launcher>
void term_derivatives(Launcher& launch, const PotentialBuffers& b, const double* q,
                      const PotentialWork& w, const DerivativeWork& dw,
                      const unsigned char* exact_contacts) {
  const int tets = b.tets.count, bodies = b.bodies.count, pairs = b.pairs.count;
  double* body_hessian = dw.stencil_hessian + 144 * std::size_t(tets);
  double* pair_hessian = body_hessian + 144 * std::size_t(bodies);
  double* friction_hessian = pair_hessian + 144 * std::size_t(pairs);
  launch(b.collision.count,
         PositionStage{b.collision, q, b.scripted_start, b.scripted_target, b.progress, w.x});
  launch(tets, ElasticStage{b.tets, q, true, w.tet, dw.tet_gradient, dw.stencil_hessian});
  launch(tets, DampingStage{b.tets, q, b.q_start, b.damping_stiffness, b.h, w.tet, dw.tet_gradient,
                            dw.stencil_hessian});
  launch(tets, StepSquaredScaleStage{b.tets.environment, b.h, dw.stencil_hessian, 144});
  launch(bodies, OrthogonalityStage{b.bodies, q, true, w.orthogonality, dw.potential_gradient,
                                    dw.orthogonality});
  launch(bodies, DriveStage{b.bodies, q, b.drive_target, w.drive, dw.potential_gradient});
  launch(bodies, AffineHessianStage{b.bodies, dw.orthogonality, body_hessian, b.h});
  launch(pairs,
         BarrierStage{b.pairs, w.x, exact_contacts, w.pair, dw.contact_gradient, pair_hessian});
  launch(pairs, StepSquaredScaleStage{b.pairs.environment, b.h, pair_hessian, 144});
  launch(b.friction.count,
         FrictionStage{b.friction, w.x, b.start_positions, w.contact,
                       dw.contact_gradient + 12 * std::size_t(pairs), friction_hessian});
  launch(b.friction.count,
         StepSquaredScaleStage{b.friction.environment, b.h, friction_hessian, 144});
}

// Every environment's gradient (the batch's DOFs) and Newton matrix (9 per pattern block) at q;
// the contacts' Hessians PSD-projected but where exact_contacts (per environment) says 1, as the
// CPU engine leaves them after projected_iterations (null: projected everywhere).
template <class Launcher>
void incremental_potential_derivatives(Launcher& launch, const PotentialBuffers& b,
                                       const DerivativeBuffers& d, const double* q,
                                       const PotentialWork& w, const DerivativeWork& dw,
                                       const unsigned char* exact_contacts, double* gradient,
                                       double* blocks) {
  launch(d.dof_count, ZeroStage{gradient});
  launch(d.dof_count, ZeroStage{dw.potential_gradient});
  term_derivatives(launch, b, q, w, dw, exact_contacts);
  const IncidenceBuffers fem_incidence{b.fem_vertices.count, b.fem_vertices.dof,
                                       d.fem_incidence_begin, d.fem_incidence_slots};
  launch(fem_incidence.count,
         GradientGatherStage{fem_incidence, dw.tet_gradient, dw.potential_gradient});
  launch(d.contact_incidence.count,
         ContactGatherStage{d.contact_incidence, d.contact_vertex, b.collision.rest,
                            dw.contact_gradient, dw.potential_gradient});
  launch(b.fem_vertices.count, InertiaStage{b.fem_vertices, q, b.q_tilde, w.fem_inertia, gradient});
  launch(b.bodies.count, AffineInertiaStage{b.bodies, q, b.q_tilde, w.body_inertia, gradient});
  launch(d.dof_count, CombineGradientStage{d.dof_begin, b.environment_count, b.h,
                                           dw.potential_gradient, gradient});
  launch(d.pattern.count, BlockAssemblyStage{d.pattern, d.slot_rest, dw.stencil_hessian, blocks});
  launch(b.fem_vertices.count, MassDiagonalStage{b.fem_vertices, d.diagonal, blocks});
}

// A batch's derivative structure, host-built: the contacts' vertices (the pairs', then the
// friction contacts'), which contact slots touch each DOF block, the stencils (tets, affine
// bodies, contacts) and their blocks, and each FEM vertex's diagonal block.
struct DerivativeStructure {
  std::vector<int> contact_vertex;
  ContactIncidence incidence;
  StencilSlots slots;
  BlockPattern pattern;
  std::vector<int> diagonal;
};

DerivativeStructure derivative_structure(const FemBatch& fem, const AffineBatch& affine,
                                         const CollisionBatch& collision, const ContactPairs& pairs,
                                         const FrictionContacts& friction);

// The structure and work arrays in host (HostArray) or device (DeviceArray) memory.
template <template <class> class Array>
struct DerivativeStorage {
  DerivativeStorage(const DerivativeStructure& s, const FemBatch& fem, const AffineBatch& affine,
                    const CollisionBatch& collision)
      : dof_begin(collision.dof_begin()),
        incidence_begin(fem.incidence_begin()),
        incidence_slots(fem.incidence_slots()),
        block_dof(collision.block_dof()),
        block_size(collision.block_size()),
        contact_begin(s.incidence.begin),
        contact_slots(s.incidence.slots),
        contact_vertex(s.contact_vertex),
        row(s.pattern.row),
        column(s.pattern.column),
        term_begin(s.pattern.begin),
        term_slots(s.pattern.term_slots),
        term_units(s.pattern.term_units),
        slot_rest(s.slots.rest),
        diagonal(s.diagonal),
        tet_gradient(12 * fem.rest_volume().size()),
        contact_gradient(3 * s.contact_vertex.size()),
        stencil_hessian(144 * std::size_t(s.slots.stencil_count())),
        orthogonality(81 * affine.volume().size()),
        potential_gradient(std::size_t(collision.dof_begin().back())),
        block_count(static_cast<int>(s.pattern.row.size())) {}

  DerivativeBuffers buffers() const {
    return {dof_begin.data(),
            static_cast<int>(potential_gradient.size()),
            incidence_begin.data(),
            incidence_slots.data(),
            {static_cast<int>(block_dof.size()), block_dof.data(), block_size.data(),
             contact_begin.data(), contact_slots.data()},
            contact_vertex.data(),
            {block_count, row.data(), column.data(), term_begin.data(), term_slots.data(),
             term_units.data()},
            slot_rest.data(),
            diagonal.data()};
  }
  DerivativeWork work() {
    return {tet_gradient.data(), contact_gradient.data(), stencil_hessian.data(),
            orthogonality.data(), potential_gradient.data()};
  }

  Array<int> dof_begin, incidence_begin, incidence_slots, block_dof, block_size, contact_begin,
      contact_slots, contact_vertex, row, column, term_begin, term_slots, term_units;
  Array<double> slot_rest;
  Array<int> diagonal;
  Array<double> tet_gradient, contact_gradient, stencil_hessian, orthogonality, potential_gradient;
  int block_count = 0;
};

}  // namespace grip::solver::parallel
