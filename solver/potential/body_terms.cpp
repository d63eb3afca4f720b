#include "solver/potential/body_terms.hpp"

namespace grip::solver {

// Each term adds its bodies' parts in body order, each asked of the body's kind.

void InertiaTerm::add_energy(const PotentialPoint& at, double& sum) const {
  for (const BodyModel& body : model_.bodies()) {
    body.kind->add_inertia_energy(body.local, at.q, q_tilde_, sum);
  }
}

void InertiaTerm::add_derivatives(const PotentialPoint& at, double scale,
                                  PotentialDerivatives& out) const {
  for (const BodyModel& body : model_.bodies()) {
    body.kind->add_inertia_derivatives(body.local, at.q, q_tilde_, scale, out.gradient,
                                       out.hessian);
  }
}

void DriveTerm::add_energy(const PotentialPoint& at, double& sum) const {
  for (const BodyModel& body : model_.bodies()) {
    body.kind->add_drive_energy(body.local, at.q, q_target_, sum);
  }
}

void DriveTerm::add_derivatives(const PotentialPoint& at, double scale,
                                PotentialDerivatives& out) const {
  for (const BodyModel& body : model_.bodies()) {
    body.kind->add_drive_derivatives(body.local, at.q, q_target_, scale, out.gradient, out.hessian);
  }
}

void ElasticityTerm::begin_step(const Eigen::VectorXd& q_start, double h) {
  h_ = h;
  stiffness_.resize(model_.bodies().size());
  bool any = false;
  for (std::size_t b = 0; b < model_.bodies().size(); ++b) {
    const BodyModel& body = model_.bodies()[b];
    if (!body.kind->damps(body.local)) continue;
    body.kind->damping_stiffness(body.local, q_start, stiffness_[b]);
    any = true;
  }
  if (any) q_start_ = q_start;
}

void ElasticityTerm::add_energy(const PotentialPoint& at, double& sum) const {
  for (std::size_t b = 0; b < model_.bodies().size(); ++b) {
    const BodyModel& body = model_.bodies()[b];
    body.kind->add_elastic_energy(body.local, at.q, sum);
    if (body.kind->damps(body.local)) {
      body.kind->add_damping_energy(body.local, at.q, {q_start_, stiffness_[b], h_}, sum);
    }
  }
}

void ElasticityTerm::add_derivatives(const PotentialPoint& at, double scale,
                                     PotentialDerivatives& out) const {
  for (std::size_t b = 0; b < model_.bodies().size(); ++b) {
    const BodyModel& body = model_.bodies()[b];
    const StepDamping damping{q_start_, stiffness_[b], h_};
    body.kind->add_elastic_derivatives(body.local, at.q, scale,
                                       body.kind->damps(body.local) ? &damping : nullptr,
                                       out.gradient, out.hessian);
  }
}

}  // namespace grip::solver
