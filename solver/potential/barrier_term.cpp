#include "solver/potential/barrier_term.hpp"

#include <cmath>

#include "solver/kernels/contact_barrier.hpp"
#include "solver/kernels/psd_projection.hpp"
#include "solver/potential/stencil.hpp"
#include "solver/potential/stencil_positions.hpp"

namespace grip::solver {
namespace {

using Matrix12 = Eigen::Matrix<double, 12, 12>;

// The contact's barrier (kernels/contact_barrier.hpp); none for a pair within d_hat at rest.
kernels::ContactBarrier barrier_of(const ContactCandidate& c, const Eigen::Vector3d x[4],
                                   double d_hat, double kappa, bool with_hessian) {
  if (c.near_at_rest) return {};
  return kernels::contact_barrier(c.edge_edge, c.mollifier_eps, x, d_hat, kappa, with_hessian);
}

}  // namespace

void BarrierTerm::add_energy(const PotentialPoint& at, double& sum) const {
  Eigen::Vector3d x[4];
  for (const ContactCandidate& c : at.candidates) {
    if (c.near_at_rest) continue;
    gather(at.positions, c.vertex, x);
    sum +=
        kernels::contact_barrier_value(c.edge_edge, c.mollifier_eps, x, model_.sim().d_hat, kappa_);
  }
}

void BarrierTerm::add_derivatives(const PotentialPoint& at, double scale,
                                  PotentialDerivatives& out) const {
  Eigen::Vector3d x[4];
  for (const ContactCandidate& c : at.candidates) {
    gather(at.positions, c.vertex, x);
    const kernels::ContactBarrier b =
        barrier_of(c, x, model_.sim().d_hat, kappa_, out.hessian != nullptr);
    if (b.value == 0.0 && b.gradient.isZero()) continue;
    const Stencil stencil(model_, c.vertex);
    if (!out.hessian) {
      stencil.scatter_gradient(scale * b.gradient, out.gradient);
      continue;
    }
    const Matrix12 h = out.project_contacts
                           ? Matrix12(scale * kernels::project_to_psd<12>(b.hessian))
                           : Matrix12(scale * b.hessian);
    stencil.scatter(scale * b.gradient, h, out.gradient, *out.hessian);
    if (out.kinematic_motion) {
      stencil.add_kinematic_force(h, *out.kinematic_motion, c.vertex, *out.kinematic_force);
    }
  }
}

ContactForce BarrierTerm::contact_force(const ContactCandidate& c,
                                        const Vertices& positions) const {
  const double d_hat = model_.sim().d_hat;
  Eigen::Vector3d x[4];
  gather(positions, c.vertex, x);
  ContactForce force;
  force.distance = std::sqrt(kernels::contact_squared_distance(c.edge_edge, x));
  const kernels::ContactBarrier b = barrier_of(c, x, d_hat, kappa_, false);
  force.force = -b.gradient;
  force.magnitude = c.near_at_rest ? 0.0
                                   : kernels::contact_normal_force(c.edge_edge, c.mollifier_eps, x,
                                                                   d_hat, kappa_);
  return force;
}

}  // namespace grip::solver
