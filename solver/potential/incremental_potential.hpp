#pragma once
// The incremental potential of one implicit Euler step (IPC):
//   E(x) = 1/2 |x - x_tilde|_M^2 + h^2 [ elasticity + damping + drives + kappa sum_k b(d_k)
//                                        + sum_k mu lambda_k f0(|u_k|) ]
// the sum of an inertia term and four potential-energy terms (potential/*_term.hpp; elasticity
// and damping are one). kappa is a stiffness (N/m) and lambda_k a force (N): at equilibrium
// M (x - x_tilde) / h^2 balances the physical forces. Derivatives are per element, projected to
// positive semi-definite before they are summed (projected Newton).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <vector>

#include "solver/contact/candidates.hpp"
#include "solver/model/model.hpp"
#include "solver/potential/barrier_term.hpp"
#include "solver/potential/body_terms.hpp"
#include "solver/potential/friction_term.hpp"

namespace grip::solver {

class IncrementalPotential {
 public:
  explicit IncrementalPotential(const Model& model);

  // The step's constants: the DOFs at its start, inertia target, the driven bodies' targets,
  // start positions of the collision vertices, the barrier stiffness and the step's length h.
  // Clears the friction contacts.
  void begin_step(const Eigen::VectorXd& q_start, Eigen::VectorXd q_tilde, Eigen::VectorXd q_drive,
                  Vertices start_positions, double kappa, double h);
  // The contacts frozen at this friction lag iteration.
  void set_friction(std::vector<FrictionContact> friction) {
    friction_.set_contacts(std::move(friction));
  }
  // The contacts a step taken elsewhere ended with (a data-parallel engine's): its kappa, its
  // last part's start positions and length h, and its last friction lag, so that the forces
  // between steps (contact_forces.hpp) are that step's. The other terms are left as they were.
  void adopt_contacts(Vertices start_positions, double kappa, double h,
                      std::vector<FrictionContact> friction);

  // positions: the collision vertices at q (kinematic ones where the step has moved them).
  double energy(const Eigen::VectorXd& q, const Vertices& positions,
                const std::vector<ContactCandidate>& candidates) const;

  // The gradient, and the lower triangle of the PSD-projected Hessian as triplets; with
  // `kinematic_motion`, also the force it adds to first order (PotentialDerivatives).
  void derivatives(const Eigen::VectorXd& q, const Vertices& positions,
                   const std::vector<ContactCandidate>& candidates, Eigen::VectorXd& gradient,
                   std::vector<Eigen::Triplet<double>>& hessian,
                   const Vertices* kinematic_motion = nullptr,
                   Eigen::VectorXd* kinematic_force = nullptr, bool project_contacts = true) const;
  // The gradient alone: bit for bit the one derivatives() computes at the same point.
  void gradient(const Eigen::VectorXd& q, const Vertices& positions,
                const std::vector<ContactCandidate>& candidates, Eigen::VectorXd& gradient) const;

  const BarrierTerm& barrier() const { return barrier_; }
  const FrictionTerm& friction() const { return friction_; }

 private:
  // Every term's derivatives at `at`, in the order they are summed.
  void add_derivatives(const PotentialPoint& at, PotentialDerivatives& out) const;
  // The terms multiplied by h^2, in the order they are summed.
  std::array<const PotentialTerm*, 4> potential_energies() const {
    return {&elasticity_, &drive_, &barrier_, &friction_};
  }

  const Model& model_;
  double h_ = 0.0;
  InertiaTerm inertia_;
  ElasticityTerm elasticity_;
  DriveTerm drive_;
  BarrierTerm barrier_;
  FrictionTerm friction_;
};

}  // namespace grip::solver
