#pragma once
// The incremental potential's per-body terms: inertia, 1/2 |x - x_tilde|_M^2 about the step's
// inertia target, elasticity (stable Neo-Hookean for FEM bodies, the orthogonality energy
// of affine ones) with FEM bodies' Rayleigh damping, and the drives of driven bodies. Each body's
// kind computes its part (BodySubsystem); a kind without such a part adds nothing.
#include "solver/model/model.hpp"
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

// Elasticity, and the Rayleigh damping of the FEM bodies whose material damps
// (Material::damping > 0): beta / (2 h) |x - x_start|_K^2 per body, K its elastic Hessian at the
// step's start. K is lagged like friction's normal forces, so damping is a convex quadratic
// within the step; a rigid motion of an unstressed body lies in K's null space and is not
// damped. One term for both, so that a tet's elastic and damping Hessians are summed before
// they are scattered (BodySubsystem::add_elastic_derivatives).
class ElasticityTerm : public PotentialTerm {
 public:
  explicit ElasticityTerm(const Model& model) : model_(model) {}
  // Evaluates each damped body's K at the step's start q_start.
  void begin_step(const Eigen::VectorXd& q_start, double h);

  void add_energy(const PotentialPoint& at, double& sum) const override;
  void add_derivatives(const PotentialPoint& at, double scale,
                       PotentialDerivatives& out) const override;

 private:
  const Model& model_;
  Eigen::VectorXd q_start_;
  double h_ = 0.0;
  std::vector<std::vector<Matrix12d>> stiffness_;  // per body, per tet; empty if undamped
};

}  // namespace grip::solver
