#include "solver/potential/body_terms.hpp"

#include "solver/body/body.hpp"
#include "solver/body/fem_body.hpp"

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

namespace {

bool damped(const BodyModel& body) {
  return body.type == BodyType::kFem && body.material.damping > 0.0;
}

}  // namespace

void ElasticityTerm::begin_step(const Eigen::VectorXd& q_start, double h) {
  h_ = h;
  stiffness_.resize(model_.bodies().size());
  bool any = false;
  for (std::size_t b = 0; b < model_.bodies().size(); ++b) {
    if (!damped(model_.bodies()[b])) continue;
    fem::tet_stiffness(model_.bodies()[b], q_start, stiffness_[b]);
    any = true;
  }
  if (any) q_start_ = q_start;
}

void ElasticityTerm::add_energy(const PotentialPoint& at, double& sum) const {
  for (std::size_t b = 0; b < model_.bodies().size(); ++b) {
    const BodyModel& body = model_.bodies()[b];
    add_elastic_energy(body, at.q, sum);
    if (damped(body)) fem::add_damping_energy(body, at.q, q_start_, stiffness_[b], h_, sum);
  }
}

void ElasticityTerm::add_derivatives(const PotentialPoint& at, double scale,
                                     PotentialDerivatives& out) const {
  for (std::size_t b = 0; b < model_.bodies().size(); ++b) {
    const BodyModel& body = model_.bodies()[b];
    if (damped(body)) {
      const fem::StepDamping damping{q_start_, stiffness_[b], h_};
      fem::add_elastic_derivatives(body, at.q, scale, &damping, out.gradient, out.hessian);
    } else {
      add_elastic_derivatives(body, at.q, scale, out.gradient, out.hessian);
    }
  }
}

}  // namespace grip::solver
