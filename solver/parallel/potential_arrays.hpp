#pragma once
// What the incremental potential of a batch reads (PotentialBuffers), copied into host
// (HostArray) or device (DeviceArray) memory from the host-built batches: the bodies (FemBatch,
// AffineBatch, CollisionBatch), the contacts (ContactPairs, FrictionContacts) and a step's
// constants. The data-parallel engine copies them whenever they change: the bodies once, the
// contacts at each friction lag and broad phase, the constants at each step.
#include <vector>

#include "solver/parallel/affine_batch.hpp"
#include "solver/parallel/collision_batch.hpp"
#include "solver/parallel/contact_stages.hpp"
#include "solver/parallel/fem_batch.hpp"
#include "solver/parallel/friction_stages.hpp"
#include "solver/parallel/potential_stages.hpp"

namespace grip::solver::parallel {

// A step's constants, host-built.
struct StepConstants {
  std::vector<double> h;                  // per environment, s
  std::vector<double> progress;           // per environment: scripted vertices' way, 0 to 1
  std::vector<double> q_start;            // the batch's DOFs at the step's start
  std::vector<double> q_tilde;            // the inertia target (PredictionStage and
                                          // AffinePredictionStage)
  std::vector<double> drive_target;       // the driven bodies' DOFs at their scripts' poses
  std::vector<double> damping_stiffness;  // 144 per tet: ElasticStage's Hessian at q_start
  std::vector<double> scripted_start;     // 3 per collision vertex (scripted ones read)
  std::vector<double> scripted_target;
  std::vector<double> start_positions;  // 3 per collision vertex at the step's start
};

template <template <class> class Array>
struct PotentialArrays {
  PotentialArrays(const FemBatch& fem, const AffineBatch& affine, const CollisionBatch& collision,
                  const ContactPairs& pairs, const FrictionContacts& friction,
                  const StepConstants& step)
      : tet_dofs(fem.tet_dofs()),
        tet_environment(fem.tet_environment()),
        tet_begin(fem.tet_begin()),
        rest_shape_inverse(fem.rest_shape_inverse()),
        rest_volume(fem.rest_volume()),
        mu(fem.mu()),
        lambda(fem.lambda()),
        damping(fem.damping()),
        vertex_dof(fem.vertex_dof()),
        vertex_environment(fem.vertex_environment()),
        vertex_begin(fem.vertex_begin()),
        vertex_mass(fem.vertex_mass()),
        body_dof(affine.dof()),
        body_environment(affine.environment()),
        body_begin(affine.body_begin()),
        mass_matrix(affine.mass_matrix()),
        mass_matrix_inverse(affine.mass_matrix_inverse()),
        weight_mass(affine.weight_mass()),
        body_volume(affine.volume()),
        orthogonality_stiffness(affine.orthogonality_stiffness()),
        drive_stiffness(affine.drive_stiffness()),
        motion(collision.motion()),
        collision_dof(collision.dof()),
        collision_rest(collision.rest()),
        collision_environment(collision.environment()),
        pair_vertex(pairs.vertex()),
        pair_edge_edge(pairs.edge_edge()),
        mollifier_eps(pairs.mollifier_eps()),
        pair_environment(pairs.environment()),
        pair_begin(pairs.pair_begin()),
        d_hat(pairs.d_hat()),
        kappa(pairs.kappa()),
        contact_vertex(friction.vertex()),
        tangent(friction.tangent()),
        mu_lambda(friction.mu_lambda()),
        contact_environment(friction.environment()),
        contact_begin(friction.contact_begin()),
        eps(friction.eps()),
        h(step.h),
        progress(step.progress),
        q_start(step.q_start),
        q_tilde(step.q_tilde),
        drive_target(step.drive_target),
        damping_stiffness(step.damping_stiffness),
        scripted_start(step.scripted_start),
        scripted_target(step.scripted_target),
        start_positions(step.start_positions),
        environment_count(fem.environment_count()) {}

  PotentialBuffers buffers() const {
    PotentialBuffers b;
    b.environment_count = environment_count;
    b.h = h.data();
    b.progress = progress.data();
    b.tets = {static_cast<int>(rest_volume.size()),
              tet_dofs.data(),
              tet_environment.data(),
              rest_shape_inverse.data(),
              rest_volume.data(),
              mu.data(),
              lambda.data(),
              damping.data()};
    b.tet_begin = tet_begin.data();
    b.q_start = q_start.data();
    b.damping_stiffness = damping_stiffness.data();
    b.fem_vertices = {static_cast<int>(vertex_mass.size()), vertex_dof.data(),
                      vertex_environment.data(), vertex_mass.data()};
    b.fem_vertex_begin = vertex_begin.data();
    b.bodies = {static_cast<int>(body_volume.size()),
                body_dof.data(),
                body_environment.data(),
                mass_matrix.data(),
                mass_matrix_inverse.data(),
                weight_mass.data(),
                body_volume.data(),
                orthogonality_stiffness.data(),
                drive_stiffness.data()};
    b.body_begin = body_begin.data();
    b.q_tilde = q_tilde.data();
    b.drive_target = drive_target.data();
    b.collision = {static_cast<int>(motion.size()), motion.data(), collision_dof.data(),
                   collision_rest.data(), collision_environment.data()};
    b.scripted_start = scripted_start.data();
    b.scripted_target = scripted_target.data();
    b.pairs = {static_cast<int>(pair_environment.size()),
               pair_vertex.data(),
               pair_edge_edge.data(),
               mollifier_eps.data(),
               pair_environment.data(),
               d_hat.data(),
               kappa.data()};
    b.pair_begin = pair_begin.data();
    b.friction = {static_cast<int>(contact_environment.size()),
                  contact_vertex.data(),
                  tangent.data(),
                  mu_lambda.data(),
                  contact_environment.data(),
                  eps.data()};
    b.contact_begin = contact_begin.data();
    b.start_positions = start_positions.data();
    return b;
  }

  Array<int> tet_dofs, tet_environment, tet_begin;
  Array<double> rest_shape_inverse, rest_volume, mu, lambda, damping;
  Array<int> vertex_dof, vertex_environment, vertex_begin;
  Array<double> vertex_mass;
  Array<int> body_dof, body_environment, body_begin;
  Array<double> mass_matrix, mass_matrix_inverse, weight_mass, body_volume, orthogonality_stiffness,
      drive_stiffness;
  Array<unsigned char> motion;
  Array<int> collision_dof;
  Array<double> collision_rest;
  Array<int> collision_environment;
  Array<int> pair_vertex;
  Array<unsigned char> pair_edge_edge;
  Array<double> mollifier_eps;
  Array<int> pair_environment, pair_begin;
  Array<double> d_hat, kappa;
  Array<int> contact_vertex;
  Array<double> tangent, mu_lambda;
  Array<int> contact_environment, contact_begin;
  Array<double> eps;
  Array<double> h, progress, q_start, q_tilde, drive_target, damping_stiffness, scripted_start,
      scripted_target, start_positions;
  int environment_count = 0;
};

}  // namespace grip::solver::parallel
