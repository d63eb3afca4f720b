#pragma once
// The incremental potential's per-body terms: inertia, 1/2 |x - x_tilde|_M^2 about the step's
// inertia target, and elasticity (stable Neo-Hookean for FEM bodies, the orthogonality energy
// of affine ones). Kinematic bodies have neither.
#include "solver/model.hpp"
#include "solver/potential/potential_term.hpp"

namespace grip::solver {

class InertiaTerm : public PotentialTerm {
 public:
  explicit InertiaTerm(const Model& model) : model_(model) {}
  // x_tilde = x + h v + h^2 M^-1 f_external, fixed for the step.
  void set_target(Eigen::VectorXd q_tilde) { q_tilde_ = std::move(q_tilde); }

  void add_energy(const PotentialPoint& at, double& sum) const override;
  void add_derivatives(const PotentialPoint& at, double scale,
                       PotentialDerivatives& out) const override;

 private:
  const Model& model_;
  Eigen::VectorXd q_tilde_;
};

class ElasticityTerm : public PotentialTerm {
 public:
  explicit ElasticityTerm(const Model& model) : model_(model) {}

  void add_energy(const PotentialPoint& at, double& sum) const override;
  void add_derivatives(const PotentialPoint& at, double scale,
                       PotentialDerivatives& out) const override;

 private:
  const Model& model_;
};

}  // namespace grip::solver
