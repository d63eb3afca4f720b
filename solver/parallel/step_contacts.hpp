#pragma once
// The contacts a step's solve begins with, for every environment of a batch at once, as the CPU
// engine's NewtonSolver finds them at a step's start (begin_step) and at each further friction
// lag (lag_friction): the barrier's pairs within d_hat of the positions x (the broad phase over
// x -> x and the reach filter: NewtonSolver::near) and the friction contacts lagged there
// (friction_lag_stages.hpp). A caller that renews only some environments' contacts keeps the
// others' (chosen_pairs, chosen_friction).
#include <vector>

#include "solver/parallel/friction_lag_stages.hpp"
#include "solver/parallel/newton_iteration.hpp"

namespace grip::solver::parallel {

struct StepContacts {
  ContactPairs pairs;
  FrictionContacts friction;
};

// The contacts the lag wrote (LaggedContacts' arrays, the batch's collision vertex numbering) as
// FrictionContacts, each environment with its eps_v h.
FrictionContacts friction_contacts(const std::vector<int>& vertex,
                                   const std::vector<double>& tangent,
                                   const std::vector<double>& mu_lambda,
                                   const std::vector<int>& contact_begin,
                                   const std::vector<int>& vertex_begin,
                                   const std::vector<double>& eps);

// Per environment, `fresh`'s contacts where take[e], else `kept`'s.
FrictionContacts chosen_friction(const FrictionContacts& kept, const FrictionContacts& fresh,
                                 const std::vector<unsigned char>& take);

// The friction contacts of every environment lagged at x (3 per collision vertex) over the
// candidates `found`, each environment with its eps_v h (`eps`); `at_zero_mu` as
// StepPolicy::friction_terms_at_zero_mu.
template <class Launcher>
FrictionContacts lag_friction(Launcher& launch, const NewtonBatch& nb, const HostBroadPhase& found,
                              const std::vector<double>& x, const std::vector<double>& eps,
                              bool at_zero_mu) {
  const int count = found.count();
  std::vector<int> keep(std::size_t(count) + 1);
  std::vector<double> mu_lambda(count), tangent(24 * std::size_t(count));
  const FrictionLagBuffers b{count,
                             found.vertex().data(),
                             found.edge_edge().data(),
                             found.near_at_rest().data(),
                             found.friction().data(),
                             found.mollifier_eps().data(),
                             found.environment().data(),
                             found.environment_begin().data(),
                             static_cast<int>(nb.d_hat.size()),
                             x.data(),
                             nb.d_hat.data(),
                             nb.kappa.data(),
                             at_zero_mu,
                             keep.data(),
                             mu_lambda.data(),
                             tangent.data()};
  const int total = count_lagged_contacts(launch, b);
  std::vector<int> vertex(4 * std::size_t(total)), environment(total),
      contact_begin(nb.d_hat.size() + 1);
  std::vector<double> lagged_tangent(24 * std::size_t(total)), lagged_mu_lambda(total);
  write_lagged_contacts(launch, b,
                        {vertex.data(), lagged_tangent.data(), lagged_mu_lambda.data(),
                         environment.data(), contact_begin.data()});
  return friction_contacts(vertex, lagged_tangent, lagged_mu_lambda, contact_begin,
                           nb.collision.vertex_begin(), eps);
}

// Every environment's friction lagged at x, over the broad phase's candidates there (a further
// lag: the barrier's pairs are kept, so the reach filter is not needed).
template <class Launcher>
FrictionContacts friction_at(Launcher& launch, const NewtonBatch& nb, const std::vector<double>& x,
                             const std::vector<double>& eps, bool at_zero_mu) {
  HostBroadPhase found(nb.surface);
  found.find(launch, x, x, nb.d_hat);
  return lag_friction(launch, nb, found, x, eps, at_zero_mu);
}

// Every environment's contacts at x: the barrier's pairs within d_hat and the friction lagged
// there.
template <class Launcher>
StepContacts contacts_at(Launcher& launch, const NewtonBatch& nb, const std::vector<double>& x,
                         const std::vector<double>& eps, bool at_zero_mu) {
  const newton_detail::PathCandidates c = newton_detail::path_candidates(launch, nb, x, x);
  return {newton_detail::reachable_pairs(nb, c),
          lag_friction(launch, nb, c.found, x, eps, at_zero_mu)};
}

}  // namespace grip::solver::parallel
