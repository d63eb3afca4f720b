#include "solver/potential/body_terms.hpp"

#include "solver/body/body.hpp"

namespace grip::solver {

void InertiaTerm::add_energy(const PotentialPoint& at, double& sum) const {
  for (const BodyModel& body : model_.bodies()) add_inertia_energy(body, at.q, q_tilde_, sum);
}

void InertiaTerm::add_derivatives(const PotentialPoint& at, double scale,
                                  PotentialDerivatives& out) const {
  for (const BodyModel& body : model_.bodies()) {
    add_inertia_derivatives(body, at.q, q_tilde_, scale, out.gradient, out.hessian);
  }
}

void DriveTerm::add_energy(const PotentialPoint& at, double& sum) const {
  for (const BodyModel& body : model_.bodies()) add_drive_energy(body, at.q, q_target_, sum);
}

void DriveTerm::add_derivatives(const PotentialPoint& at, double scale,
                                PotentialDerivatives& out) const {
  for (const BodyModel& body : model_.bodies()) {
    add_drive_derivatives(body, at.q, q_target_, scale, out.gradient, out.hessian);
  }
}

void ElasticityTerm::add_energy(const PotentialPoint& at, double& sum) const {
  for (const BodyModel& body : model_.bodies()) add_elastic_energy(body, at.q, sum);
}

void ElasticityTerm::add_derivatives(const PotentialPoint& at, double scale,
                                     PotentialDerivatives& out) const {
  for (const BodyModel& body : model_.bodies()) {
    add_elastic_derivatives(body, at.q, scale, out.gradient, out.hessian);
  }
}

}  // namespace grip::solver
