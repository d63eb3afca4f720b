#pragma once
// The filters a Newton step passes before it is taken, in order: continuous collision detection
// (the largest fraction of the step that keeps every contact apart), positive volumes (halving
// until no tet inverts), and Armijo's sufficient decrease of the incremental potential.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "solver/contact/candidates.hpp"
#include "solver/model/model.hpp"
#include "solver/newton/step_targets.hpp"
#include "solver/potential/incremental_potential.hpp"

namespace grip::solver {

// The largest fraction (at most 1) of the motion start -> end that no candidate's additive CCD
// finds colliding.
double collision_free_fraction(const std::vector<ContactCandidate>& candidates,
                               const Vertices& start, const Vertices& end, double rescaling);

// Halves alpha until q + alpha p inverts no tet; false when alpha falls below 1e-12. Counts the
// halvings.
bool halve_until_no_inversion(const Model& model, const Eigen::VectorXd& q,
                              const Eigen::VectorXd& p, double& alpha, int& halvings);

// Halves alpha until the potential at q + alpha p decreases sufficiently (Armijo, c = 1e-4)
// against its value `energy` and slope at q; `accept_any` (a held step) takes alpha as it is.
// False when alpha falls below 1e-12. Counts the halvings.
bool armijo(const IncrementalPotential& potential, const Model& model, const StepTargets& targets,
            const std::vector<ContactCandidate>& candidates, const Eigen::VectorXd& q,
            const Eigen::VectorXd& p, double energy, double slope, bool accept_any, double& alpha,
            int& halvings);

}  // namespace grip::solver
