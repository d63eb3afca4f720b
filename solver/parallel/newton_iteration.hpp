#pragma once
// One Newton iteration of every environment of a batch at once, on a host launcher: the
// data-parallel engine's stages strung together as the CPU engine's NewtonSolver::iterate takes
// one environment's (solver/newton/newton_solver.cpp):
//   1. the Newton system at q (newton_system.hpp: derivative_stages.hpp's, with the force of
//      prescribed motion still to come); a non-finite gradient fails;
//   2. the residual over free DOFs against the solve's first (never less than the dynamic
//      bodies' standard weight times h^2): converged at newton_tol once prescribed motion is
//      done and the step is not held open;
//   3. the Newton step by block-Jacobi CG (block_pcg.hpp), or by dense Cholesky where the batch
//      says so (dense_cholesky.hpp), the fixed DOFs keeping their motion;
//      converged when it would move no vertex more than newton_velocity_tol h;
//   4. the line search: the broad phase over the path from x to the step's end and the reach
//      filter (broad_phase.hpp, reach_stages.hpp), CCD's bound over the pairs it watches
//      (ccd_stages.hpp), halving until no tet inverts, then (prescribed motion done, the step
//      not held) Armijo's sufficient decrease with the barrier over the pairs within reach
//      (line_search_stages.hpp);
//   5. the commit of each environment's step by its own alpha, its progress, and its pairs
//      within reach as the barrier's next.
// Each environment has its own outcome and failure; one that is idle (converged or failed
// before) or stops this iteration is left as it is. The contacts' Hessians are PSD-projected in
// a solve's first projected_iterations iterations and left exact after, and projected after all
// where CG finds the matrix indefinite (the CPU engine projects them where its factorization
// refuses it). Where the CPU engine differs: the linear solve is CG to each environment's
// cg_tolerance (the CPU engine factorizes, and solves by CG on an earlier factorization to
// reuse_tolerance in between), and a batch shares one ccd_rescaling. The host builds the contacts'
// structures (derivative_structure, the PCG's pattern) and the barrier's pairs each iteration; the
// engine on a GPU will keep them there.
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "solver/parallel/affine_batch.hpp"
#include "solver/parallel/block_pcg.hpp"
#include "solver/parallel/broad_phase.hpp"
#include "solver/parallel/ccd_stages.hpp"
#include "solver/parallel/collision_batch.hpp"
#include "solver/parallel/contact_stages.hpp"
#include "solver/parallel/dense_cholesky.hpp"
#include "solver/parallel/derivative_stages.hpp"
#include "solver/parallel/fem_batch.hpp"
#include "solver/parallel/friction_stages.hpp"
#include "solver/parallel/line_search_stages.hpp"
#include "solver/parallel/map_stages.hpp"
#include "solver/parallel/newton_stages.hpp"
#include "solver/parallel/newton_system.hpp"
#include "solver/parallel/potential_arrays.hpp"
#include "solver/parallel/prescribed_motion_stages.hpp"
#include "solver/parallel/reach_stages.hpp"
#include "solver/parallel/surface_batch.hpp"

namespace grip::solver::parallel {

// What became of an environment in an iteration.
enum NewtonOutcome : int {
  kNewtonIdle = 0,       // not iterating (converged or failed before)
  kNewtonContinue = 1,   // took a step and iterates on
  kNewtonConverged = 2,  // the step's solve is done
  kNewtonFailed = 3      // see NewtonFailure
};

// Why an environment's iteration failed: the CPU engine's Failure codes of an iteration.
enum NewtonFailure : int {
  kNewtonNoFailure = 0,
  kNewtonNonFinite = 1,    // a gradient or Newton step that is not a number
  kNewtonLinearSolve = 2,  // CG did not converge (or the matrix was not SPD)
  kNewtonNoMotion = 3,     // CCD allows no motion
  kNewtonInversion = 4,    // no fraction of the step keeps every tet positively oriented
  kNewtonNoDecrease = 5    // the line search cannot decrease the incremental potential
};

// CG's relative residual where a solve should be as good as a direct one.
constexpr double kExactCgTolerance = 1e-10;

// What an iteration reads that its step holds fixed: the batch's bodies, its pinned and fixed
// DOFs, and per environment its parameters.
struct NewtonBatch {
  NewtonBatch(const FemBatch& fem, const AffineBatch& affine, const CollisionBatch& collision,
              const SurfaceBatch& surface)
      : fem(fem), affine(affine), collision(collision), surface(surface) {}

  const FemBatch& fem;
  const AffineBatch& affine;
  const CollisionBatch& collision;
  const SurfaceBatch& surface;
  std::vector<char> prescribed;           // per DOF: a pin prescribes it
  std::vector<char> fixed;                // per DOF: prescribed, or held by a fixture
  std::vector<double> prescribed_target;  // per DOF (read where prescribed)
  // Per environment: SimParameters' d_hat, newton_tol and newton_velocity_tol, the barrier's
  // kappa, the dynamic bodies' weight under standard gravity (N), whether the step is held open.
  // SimParameters::projected_iterations.
  std::vector<double> d_hat, kappa, newton_tol, velocity_tol, standard_weight;
  std::vector<unsigned char> held;
  std::vector<int> projected_iterations;
  // Per environment: 1 where its Newton system is solved by dense Cholesky (a rigid object and
  // a hand's driven links), else by CG; empty: CG for all.
  std::vector<unsigned char> dense;
  double ccd_rescaling = 0.1;  // SimParameters::ccd_rescaling, one for the batch
  // Per environment: CG's relative residual; empty: kExactCgTolerance for all.
  std::vector<double> cg_tolerance;
  int cg_iterations = 10000;
};

// Where every environment's step stands between iterations.
struct NewtonIterate {
  StepConstants step;                  // its progress advances with each commit
  std::vector<double> q;               // the batch's DOFs
  ContactPairs pairs;                  // the barrier's: within reach on the last step's path
  FrictionContacts friction;           // the friction lag's
  std::vector<unsigned char> active;   // per environment: still iterating
  std::vector<int> iteration;          // per environment: iterations of its current solve
  std::vector<double> first_residual;  // per environment; negative until taken
  // Per environment: the last step was whole and started within sqrt(newton_tol) of the
  // residual's scale, so this iteration is expected to converge.
  std::vector<unsigned char> convergence_expected;
  // Per environment, what the last iteration found (NewtonOutcome, NewtonFailure), its residual
  // (N s^2, the largest free gradient entry), the fraction of its step it took, and the CG
  // iterations its solves took (0 where dense Cholesky solved it).
  std::vector<int> outcome, failure;
  std::vector<double> residual, alpha;
  std::vector<int> cg_iterations;
};

// The barrier's pairs of every environment: the broad phase's candidates in `found` that
// `list` holds (indices, each environment's from list_begin[e]), leaving out those near at rest.
ContactPairs pairs_of(const HostBroadPhase& found, const std::vector<int>& list,
                      const std::vector<int>& list_begin, const std::vector<int>& vertex_begin,
                      const std::vector<double>& d_hat, const std::vector<double>& kappa);

// Per environment, `fresh`'s pairs where take[e], else `kept`'s.
ContactPairs chosen_pairs(const ContactPairs& kept, const ContactPairs& fresh,
                          const std::vector<unsigned char>& take);

namespace newton_detail {

inline bool moving(const NewtonIterate& it, int e) { return it.step.progress[e] < 1.0; }

inline bool continues(const NewtonIterate& it, int e) { return it.outcome[e] == kNewtonContinue; }

inline void fail(NewtonIterate& it, int e, NewtonFailure why) {
  it.outcome[e] = kNewtonFailed;
  it.failure[e] = why;
}

// Whether v[begin, end) holds numbers only.
inline bool finite_range(const std::vector<double>& v, int begin, int end) {
  for (int i = begin; i < end; ++i) {
    if (!std::isfinite(v[i])) return false;
  }
  return true;
}

template <class Launcher>
NewtonSystem newton_system(Launcher& launch, const NewtonBatch& nb, const NewtonIterate& it,
                           const std::vector<unsigned char>& exact) {
  return parallel::newton_system(launch, nb.fem, nb.affine, nb.collision, it.pairs, it.friction,
                                 it.step, it.q, exact.data());
}

// Steps 1 and 2: each active environment's residual, its scale, and convergence by it.
template <class Launcher>
NewtonSystem evaluate(Launcher& launch, const NewtonBatch& nb, NewtonIterate& it,
                      const std::vector<unsigned char>& exact) {
  NewtonSystem s = newton_system(launch, nb, it, exact);
  const std::vector<int>& dof_begin = nb.collision.dof_begin();
  const int environments = static_cast<int>(it.active.size());
  launch(environments, FreeResidualStage{dof_begin.data(), nb.fixed.data(), s.gradient.data(),
                                         it.residual.data()});
  for (int e = 0; e < environments; ++e) {
    it.outcome[e] = it.active[e] != 0 ? kNewtonContinue : kNewtonIdle;
    if (!continues(it, e)) continue;
    if (!finite_range(s.gradient, dof_begin[e], dof_begin[e + 1])) {
      fail(it, e, kNewtonNonFinite);
      continue;
    }
    const double tol = nb.newton_tol[e], residual = it.residual[e], h = it.step.h[e];
    if (it.convergence_expected[e] != 0 && residual <= tol * it.first_residual[e]) {
      it.outcome[e] = kNewtonConverged;
      continue;
    }
    if (it.first_residual[e] < 0.0) {
      it.first_residual[e] = std::max(residual, nb.standard_weight[e] * h * h);
    }
    if (!moving(it, e) && nb.held[e] == 0 && residual <= tol * it.first_residual[e]) {
      it.outcome[e] = kNewtonConverged;
    }
  }
  return s;
}

// The Newton step p of the environments `wanted` marks, by CG or dense Cholesky (NewtonBatch::
// dense), their fixed DOFs' motion kept (the others' p holds their fixed values alone), and each
// one's status as CG's (a dense factorization that finds the matrix not positive definite is
// CG's indefinite); their CG iterations are added to it.cg_iterations.
template <class Launcher>
std::vector<double> solve(Launcher& launch, const NewtonBatch& nb, NewtonIterate& it,
                          const NewtonSystem& s, const std::vector<unsigned char>& wanted,
                          std::vector<int>& status) {
  const std::vector<int>& dof_begin = nb.collision.dof_begin();
  const int dofs = static_cast<int>(it.q.size()), environments = static_cast<int>(it.active.size());
  std::vector<double> rhs(dofs), p(dofs);
  launch(dofs,
         NewtonRightHandSideStage{nb.fixed.data(), s.gradient.data(), s.force.data(), rhs.data()});
  launch(dofs, FixedMotionStage{dof_begin.data(), environments, it.step.progress.data(),
                                nb.prescribed.data(), nb.prescribed_target.data(), it.q.data(),
                                p.data()});
  std::vector<unsigned char> skip(environments), dense(environments);
  for (int e = 0; e < environments; ++e) {
    const bool direct = !nb.dense.empty() && nb.dense[e] != 0;
    skip[e] = wanted[e] == 0 || direct;
    dense[e] = wanted[e] != 0 && direct;
  }
  HostPcg pcg(nb.fem, nb.affine, s.structure.pattern, dof_begin);
  const std::vector<double> tolerance = nb.cg_tolerance.empty()
                                            ? std::vector<double>(environments, kExactCgTolerance)
                                            : nb.cg_tolerance;
  pcg.solve(launch, s.blocks, nb.fixed, rhs, tolerance, nb.cg_iterations, p, skip.data());
  status = pcg.status();
  for (int e = 0; e < environments; ++e) it.cg_iterations[e] += pcg.iterations()[e];
  if (std::none_of(dense.begin(), dense.end(), [](unsigned char d) { return d != 0; })) return p;
  const BlockPattern& pattern = s.structure.pattern;
  const std::vector<long long> matrix_begin = dense_matrix_begin(dof_begin, dense.data());
  std::vector<double> matrix(static_cast<std::size_t>(matrix_begin.back()));
  std::vector<int> dense_status(environments);
  launch(environments,
         DenseCholeskyStage{
             {environments, dof_begin.data(), pattern.environment_begin.data(), pattern.row.data(),
              pattern.column.data(), s.blocks.data(), nb.fixed.data(), rhs.data(),
              matrix_begin.data(), matrix.data(), p.data(), dense_status.data()},
             dense.data()});
  for (int e = 0; e < environments; ++e) {
    if (dense[e] != 0) status[e] = dense_status[e] == kDenseSolved ? kPcgConverged : kPcgIndefinite;
  }
  return p;
}

// Step 3: the Newton step of every environment that goes on; where its exact matrix is found
// indefinite, its system again with the contacts projected (the others' solves kept).
template <class Launcher>
std::vector<double> newton_step(Launcher& launch, const NewtonBatch& nb, NewtonIterate& it,
                                NewtonSystem& s, std::vector<unsigned char>& exact) {
  const int environments = static_cast<int>(it.active.size());
  std::vector<unsigned char> wanted(environments), again(environments);
  for (int e = 0; e < environments; ++e) wanted[e] = continues(it, e) ? 1 : 0;
  std::vector<int> status;
  std::vector<double> p = solve(launch, nb, it, s, wanted, status);
  for (int e = 0; e < environments; ++e) {
    if (wanted[e] == 0 || exact[e] == 0) continue;
    if (status[e] == kPcgIndefinite || status[e] == kPcgBadPreconditioner) {
      exact[e] = 0;
      again[e] = 1;
    }
  }
  const std::vector<int>& dof_begin = nb.collision.dof_begin();
  if (std::any_of(again.begin(), again.end(), [](unsigned char a) { return a != 0; })) {
    s = newton_system(launch, nb, it, exact);
    std::vector<int> projected_status;
    const std::vector<double> projected = solve(launch, nb, it, s, again, projected_status);
    for (int e = 0; e < environments; ++e) {
      if (again[e] == 0) continue;
      status[e] = projected_status[e];
      std::copy(projected.begin() + dof_begin[e], projected.begin() + dof_begin[e + 1],
                p.begin() + dof_begin[e]);
    }
  }
  std::vector<double> displacement(environments);
  launch(environments, StepDisplacementStage{
                           nb.fem.vertices(), nb.fem.vertex_begin().data(), nb.collision.vertices(),
                           nb.collision.vertex_begin().data(), p.data(), displacement.data()});
  for (int e = 0; e < environments; ++e) {
    if (!continues(it, e)) continue;
    if (status[e] != kPcgConverged) {
      fail(it, e, kNewtonLinearSolve);
    } else if (!finite_range(p, dof_begin[e], dof_begin[e + 1])) {
      fail(it, e, kNewtonNonFinite);
    } else if (!moving(it, e) && nb.held[e] == 0 &&
               displacement[e] <= nb.velocity_tol[e] * it.step.h[e]) {
      it.outcome[e] = kNewtonConverged;
    }
  }
  return p;
}

// The collision vertices at the end of the step p, its prescribed motion done.
template <class Launcher>
std::vector<double> step_end(Launcher& launch, const NewtonBatch& nb, const NewtonIterate& it,
                             const std::vector<double>& p) {
  std::vector<double> q_end(it.q.size()), x_end(3 * std::size_t(nb.collision.vertex_count()));
  for (std::size_t d = 0; d < q_end.size(); ++d) q_end[d] = it.q[d] + p[d];
  const std::vector<double> done(it.active.size(), 1.0);
  launch(nb.collision.vertex_count(),
         PositionStage{nb.collision.vertices(), q_end.data(), it.step.scripted_start.data(),
                       it.step.scripted_target.data(), done.data(), x_end.data()});
  return x_end;
}

// The candidates of every environment's path x -> x_end (the broad phase) and the reach
// filter's lists over them: the pairs within reach, and those CCD watches.
struct PathCandidates {
  HostBroadPhase found;
  ReachStorage<HostArray> reach;
  int reachable = 0, watched = 0;
};

template <class Launcher>
PathCandidates path_candidates(Launcher& launch, const NewtonBatch& nb,
                               const std::vector<double>& x, const std::vector<double>& x_end) {
  HostBroadPhase found(nb.surface);
  found.find(launch, x, x_end, nb.d_hat);
  const SurfaceBuffers surface = nb.surface.buffers();
  const int count = found.count();
  PathCandidates c{std::move(found), ReachStorage<HostArray>(surface, count)};
  const std::vector<double> rescaling(nb.d_hat.size(), nb.ccd_rescaling);
  find_within_reach(
      launch,
      c.reach.buffers(surface, x.data(), x_end.data(), nb.d_hat.data(), rescaling.data(), count,
                      c.found.vertex().data(), c.found.edge_edge().data(),
                      c.found.environment().data(), c.found.environment_begin().data()),
      c.reachable, c.watched);
  return c;
}

// The barrier's pairs among `c`: those within reach, less those near at rest.
inline ContactPairs reachable_pairs(const NewtonBatch& nb, const PathCandidates& c) {
  return pairs_of(c.found, c.reach.reachable, c.reach.reachable_begin, nb.collision.vertex_begin(),
                  nb.d_hat, nb.kappa);
}

// Step 4 up to CCD: the path's candidates, the pairs within reach (as the barrier's pairs) and
// each environment's CCD bound in it.alpha.
template <class Launcher>
ContactPairs path_bound(Launcher& launch, const NewtonBatch& nb, NewtonIterate& it,
                        const std::vector<double>& x, const std::vector<double>& x_end) {
  const PathCandidates c = path_candidates(launch, nb, x, x_end);
  const int watched = c.watched;
  std::vector<int> vertex(4 * std::size_t(watched));
  std::vector<unsigned char> edge_edge(watched);
  for (int k = 0; k < watched; ++k) {
    const int candidate = c.reach.ccd[k];
    for (int i = 0; i < 4; ++i) vertex[4 * k + i] = c.found.vertex()[4 * candidate + i];
    edge_edge[k] = c.found.edge_edge()[candidate];
  }
  std::vector<double> toi(watched);
  launch(watched, CcdStage{vertex.data(), edge_edge.data(), x.data(), x_end.data(),
                           nb.ccd_rescaling, toi.data()});
  launch(static_cast<int>(it.active.size()),
         EnvironmentMinStage{c.reach.ccd_begin.data(), toi.data(), it.alpha.data()});
  for (int e = 0; e < static_cast<int>(it.active.size()); ++e) {
    if (continues(it, e) && !(it.alpha[e] > 0.0)) fail(it, e, kNewtonNoMotion);
  }
  return reachable_pairs(nb, c);
}

// Step 4 after CCD: halving until no tet inverts, then sufficient decrease with the barrier
// over `within_reach`, each environment from its CCD bound.
template <class Launcher>
void line_search(Launcher& launch, const NewtonBatch& nb, NewtonIterate& it,
                 const std::vector<double>& p, const std::vector<double>& gradient,
                 const ContactPairs& within_reach) {
  const int environments = static_cast<int>(it.active.size());
  std::vector<int> halvings(environments), status(environments), halving(1);
  std::vector<double> ratio(nb.fem.rest_volume().size()), smallest(environments);
  halve_until_no_inversion(
      launch, StepHalvingBuffers{nb.fem.tets(), nb.fem.tet_begin().data(), environments,
                                 it.q.data(), p.data(), it.alpha.data(), halvings.data(),
                                 status.data(), ratio.data(), smallest.data(), halving.data()});
  std::vector<unsigned char> accept_any(environments);
  for (int e = 0; e < environments; ++e) {
    if (continues(it, e) && status[e] == kStepTooSmall) fail(it, e, kNewtonInversion);
    accept_any[e] = !continues(it, e) || moving(it, e) || nb.held[e] != 0;
  }
  const PotentialArrays<HostArray> arrays(nb.fem, nb.affine, nb.collision, within_reach,
                                          it.friction, it.step);
  const PotentialBuffers b = arrays.buffers();
  PotentialStorage<HostArray> work(b);
  SufficientDecreaseStorage<HostArray> search(nb.collision.dof_begin());
  sufficient_decrease(launch, search.buffers(b, work.work(), it.q.data(), p.data(), gradient.data(),
                                             accept_any.data(), it.alpha.data()));
  for (int e = 0; e < environments; ++e) {
    if (continues(it, e) && search.status[e] == kNoDecrease) fail(it, e, kNewtonNoDecrease);
  }
}

// Step 5.
template <class Launcher>
void commit(Launcher& launch, const NewtonBatch& nb, NewtonIterate& it,
            const std::vector<double>& p, const ContactPairs& within_reach) {
  const int environments = static_cast<int>(it.active.size());
  std::vector<unsigned char> take(environments);
  for (int e = 0; e < environments; ++e) {
    take[e] = continues(it, e) ? 1 : 0;
    if (take[e] == 0) continue;
    it.convergence_expected[e] =
        it.alpha[e] >= 1.0 && !moving(it, e) && nb.held[e] == 0 &&
        it.residual[e] <= std::sqrt(nb.newton_tol[e]) * it.first_residual[e];
  }
  const std::vector<int>& dof_begin = nb.collision.dof_begin();
  launch(static_cast<int>(it.q.size()), CommitStage{dof_begin.data(), environments, take.data(),
                                                    it.alpha.data(), p.data(), it.q.data()});
  launch(environments, ProgressStage{take.data(), it.alpha.data(), it.step.progress.data()});
  it.pairs = chosen_pairs(it.pairs, within_reach, take);
}

}  // namespace newton_detail

// One iteration of every active environment (it.active): it.outcome says what became of each.
template <class Launcher>
void newton_iteration(Launcher& launch, const NewtonBatch& nb, NewtonIterate& it) {
  using namespace newton_detail;
  const std::size_t environments = it.active.size();
  it.outcome.assign(environments, kNewtonIdle);
  it.failure.assign(environments, kNewtonNoFailure);
  it.residual.assign(environments, 0.0);
  it.alpha.assign(environments, 0.0);
  it.cg_iterations.assign(environments, 0);
  std::vector<unsigned char> exact(environments);
  for (std::size_t e = 0; e < environments; ++e) {
    if (it.active[e] == 0) continue;
    exact[e] = ++it.iteration[e] > nb.projected_iterations[e] ? 1 : 0;
  }
  NewtonSystem s = evaluate(launch, nb, it, exact);
  const std::vector<double> p = newton_step(launch, nb, it, s, exact);
  const std::vector<double> x_end = step_end(launch, nb, it, p);
  const ContactPairs within_reach = path_bound(launch, nb, it, s.x, x_end);
  line_search(launch, nb, it, p, s.gradient, within_reach);
  commit(launch, nb, it, p, within_reach);
}

}  // namespace grip::solver::parallel
