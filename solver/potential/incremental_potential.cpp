#include "solver/potential/incremental_potential.hpp"

namespace grip::solver {

IncrementalPotential::IncrementalPotential(const Model& model)
    : model_(model),
      inertia_(model),
      elasticity_(model),
      drive_(model),
      barrier_(model),
      friction_(model) {}

void IncrementalPotential::begin_step(const Eigen::VectorXd& q_start, Eigen::VectorXd q_tilde,
                                      Eigen::VectorXd q_drive, Vertices start_positions,
                                      double kappa, double h) {
  h_ = h;
  elasticity_.begin_step(q_start, h);
  inertia_.set_target(std::move(q_tilde));
  drive_.set_target(std::move(q_drive));
  barrier_.set_kappa(kappa);
  friction_.begin_step(std::move(start_positions), h);
}

void IncrementalPotential::adopt_contacts(Vertices start_positions, double kappa, double h,
                                          std::vector<FrictionContact> friction) {
  barrier_.set_kappa(kappa);
  friction_.begin_step(std::move(start_positions), h);
  friction_.set_contacts(std::move(friction));
}

double IncrementalPotential::energy(const Eigen::VectorXd& q, const Vertices& positions,
                                    const std::vector<ContactCandidate>& candidates) const {
  const PotentialPoint at{q, positions, candidates};
  double inertia = 0.0;
  inertia_.add_energy(at, inertia);
  double potential = 0.0;
  for (const PotentialTerm* term : potential_energies()) term->add_energy(at, potential);
  return inertia + h_ * h_ * potential;
}

void IncrementalPotential::derivatives(const Eigen::VectorXd& q, const Vertices& positions,
                                       const std::vector<ContactCandidate>& candidates,
                                       Eigen::VectorXd& gradient,
                                       std::vector<Eigen::Triplet<double>>& hessian,
                                       const Vertices* kinematic_motion,
                                       Eigen::VectorXd* kinematic_force,
                                       bool project_contacts) const {
  gradient.setZero(model_.dof_count());
  hessian.clear();
  if (kinematic_force) kinematic_force->setZero(model_.dof_count());
  PotentialDerivatives out{gradient, &hessian, kinematic_motion, kinematic_force, project_contacts};
  add_derivatives({q, positions, candidates}, out);
}

void IncrementalPotential::gradient(const Eigen::VectorXd& q, const Vertices& positions,
                                    const std::vector<ContactCandidate>& candidates,
                                    Eigen::VectorXd& gradient) const {
  gradient.setZero(model_.dof_count());
  PotentialDerivatives out{gradient, nullptr};
  add_derivatives({q, positions, candidates}, out);
}

void IncrementalPotential::add_derivatives(const PotentialPoint& at,
                                           PotentialDerivatives& out) const {
  inertia_.add_derivatives(at, 1.0, out);
  const double h2 = h_ * h_;
  for (const PotentialTerm* term : potential_energies()) term->add_derivatives(at, h2, out);
}

}  // namespace grip::solver
