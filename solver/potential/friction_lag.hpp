#pragma once
// The friction lag: the contacts that push at `positions`, each frozen with its normal force
// lambda (times mu) and its tangent frame, for the next solve's friction term.
#include <vector>

#include "solver/contact/candidates.hpp"
#include "solver/model/model.hpp"
#include "solver/potential/barrier_term.hpp"
#include "solver/potential/friction_term.hpp"

namespace grip::solver {

// `near` holds every pair within d_hat of `positions` (find_contact_candidates). Contacts of
// pairs with mu = 0 are left out unless `at_zero_mu` (StepPolicy).
std::vector<FrictionContact> lag_friction(const BarrierTerm& barrier, const Vertices& positions,
                                          const std::vector<ContactCandidate>& near,
                                          bool at_zero_mu);

}  // namespace grip::solver
