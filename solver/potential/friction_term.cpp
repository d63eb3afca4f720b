#include "solver/potential/friction_term.hpp"

#include "solver/kernels/friction_potential.hpp"
#include "solver/potential/stencil.hpp"
#include "solver/potential/stencil_positions.hpp"

namespace grip::solver {

using Vector12 = Eigen::Matrix<double, 12, 1>;
using Matrix12 = Eigen::Matrix<double, 12, 12>;

void FrictionTerm::begin_step(Vertices start_positions, double h) {
  eps_ = model_.sim().eps_v * h;
  start_ = std::move(start_positions);
  contacts_.clear();
}

Vector12 FrictionTerm::displacement(const FrictionContact& contact,
                                    const Vertices& positions) const {
  Eigen::Vector3d x[4];
  Eigen::Vector3d x0[4];
  gather(positions, contact.vertex, x);
  gather(start_, contact.vertex, x0);
  return stack(x) - stack(x0);
}

void FrictionTerm::add_energy(const PotentialPoint& at, double& sum) const {
  for (const FrictionContact& c : contacts_) {
    sum += kernels::friction_potential<4>(displacement(c, at.positions), c.tangent_operator,
                                          c.mu_lambda, eps_);
  }
}

void FrictionTerm::add_derivatives(const PotentialPoint& at, double scale,
                                   PotentialDerivatives& out) const {
  for (const FrictionContact& c : contacts_) {
    const Vector12 dx = displacement(c, at.positions);
    const Stencil stencil(model_, c.vertex);
    const Vector12 g =
        scale * kernels::friction_potential_gradient<4>(dx, c.tangent_operator, c.mu_lambda, eps_);
    if (!out.hessian) {
      stencil.scatter_gradient(g, out.gradient);
      continue;
    }
    const Matrix12 h =
        scale * kernels::friction_potential_hessian<4>(dx, c.tangent_operator, c.mu_lambda, eps_);
    stencil.scatter(g, h, out.gradient, *out.hessian);
    if (out.kinematic_motion) {
      stencil.add_kinematic_force(h, *out.kinematic_motion, c.vertex, *out.kinematic_force);
    }
  }
}

Vector12 FrictionTerm::force(const FrictionContact& contact, const Vertices& positions) const {
  return -kernels::friction_potential_gradient<4>(
      displacement(contact, positions), contact.tangent_operator, contact.mu_lambda, eps_);
}

}  // namespace grip::solver
