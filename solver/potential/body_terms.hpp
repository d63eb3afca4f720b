#pragma once
// The incremental potential's per-body terms: inertia, 1/2 |x - x_tilde|_M^2 about the step's
// inertia target, elasticity (stable Neo-Hookean for FEM bodies, the orthogonality energy
// of affine ones) and the drives of driven bodies. Kinematic bodies have none.
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

// The springs that pull driven bodies towards their scripts' poses at the end of the step.
class DriveTerm : public PotentialTerm {
 public:
  explicit DriveTerm(const Model& model) : model_(model) {}
  // The DOFs of each driven body at its script's pose at the end of the step (other entries
  // unused).
  void set_target(Eigen::VectorXd q_target) { q_target_ = std::move(q_target); }

  void add_energy(const PotentialPoint& at, double& sum) const override;
  void add_derivatives(const PotentialPoint& at, double scale,
                       PotentialDerivatives& out) const override;

 private:
  const Model& model_;
  Eigen::VectorXd q_target_;
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
