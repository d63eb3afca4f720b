#include "solver/potential/barrier_term.hpp"

#include <cmath>

#include "solver/kernels/barrier.hpp"
#include "solver/kernels/distance.hpp"
#include "solver/kernels/edge_edge_mollifier.hpp"
#include "solver/kernels/psd_projection.hpp"
#include "solver/potential/stencil.hpp"
#include "solver/potential/stencil_positions.hpp"

namespace grip::solver {
namespace {

using Vector12 = Eigen::Matrix<double, 12, 1>;
using Matrix12 = Eigen::Matrix<double, 12, 12>;

double squared_distance(const ContactCandidate& c, const Eigen::Vector3d x[4]) {
  return c.edge_edge ? kernels::edge_edge_distance_sq(x[0], x[1], x[2], x[3])
                     : kernels::point_triangle_distance_sq(x[0], x[1], x[2], x[3]);
}

struct Barrier {
  double value = 0.0;
  Vector12 gradient = Vector12::Zero();
  Matrix12 hessian = Matrix12::Zero();
};

// The squared distance's gradient and (optionally) Hessian in the four vertices' positions.
void squared_distance_derivatives(const ContactCandidate& c, const Eigen::Vector3d x[4],
                                  bool with_hessian, Vector12& grad_s, Matrix12& hess_s) {
  if (c.edge_edge) {
    grad_s = kernels::edge_edge_distance_sq_gradient(x[0], x[1], x[2], x[3]);
    if (with_hessian) hess_s = kernels::edge_edge_distance_sq_hessian(x[0], x[1], x[2], x[3]);
  } else {
    grad_s = kernels::point_triangle_distance_sq_gradient(x[0], x[1], x[2], x[3]);
    if (with_hessian) hess_s = kernels::point_triangle_distance_sq_hessian(x[0], x[1], x[2], x[3]);
  }
}

// kappa m b from kappa b's derivatives (grad_b, hess_b) and the mollifier of nearly parallel
// edges: the product rule.
void mollify(const Eigen::Vector3d x[4], double eps, double kappa, double b, const Vector12& grad_b,
             const Matrix12& hess_b, bool with_hessian, Barrier& result) {
  const double m = kernels::edge_edge_mollifier(x[0], x[1], x[2], x[3], eps);
  result.value = kappa * m * b;
  if (m == 1.0) {
    result.gradient = kappa * grad_b;
    if (with_hessian) result.hessian = kappa * hess_b;
    return;
  }
  const Vector12 grad_m = kernels::edge_edge_mollifier_gradient(x[0], x[1], x[2], x[3], eps);
  result.gradient = kappa * (m * grad_b + b * grad_m);
  if (with_hessian) {
    const Matrix12 hess_m = kernels::edge_edge_mollifier_hessian(x[0], x[1], x[2], x[3], eps);
    result.hessian = kappa * (m * hess_b + grad_m * grad_b.transpose() +
                              grad_b * grad_m.transpose() + b * hess_m);
  }
}

// kappa m b(d) and its derivatives in the four vertices' positions, with d = sqrt(s):
// db/ds = b'(d) / (2d), d2b/ds2 = (b''(d) - b'(d) / d) / (4 s).
Barrier barrier_of(const ContactCandidate& c, const Eigen::Vector3d x[4], double d_hat,
                   double kappa, bool with_hessian) {
  Barrier result;
  if (c.near_at_rest) return result;
  const double s = squared_distance(c, x);
  if (s >= d_hat * d_hat) return result;
  const double d = std::sqrt(s);
  const double b = kernels::barrier(d, d_hat);
  const double b1 = kernels::barrier_first_derivative(d, d_hat);
  const double db_ds = b1 / (2.0 * d);
  Vector12 grad_s;
  Matrix12 hess_s;
  squared_distance_derivatives(c, x, with_hessian, grad_s, hess_s);
  const Vector12 grad_b = db_ds * grad_s;
  Matrix12 hess_b;
  if (with_hessian) {
    const double d2b_ds2 = (kernels::barrier_second_derivative(d, d_hat) - b1 / d) / (4.0 * s);
    hess_b = d2b_ds2 * grad_s * grad_s.transpose() + db_ds * hess_s;
  }
  if (c.edge_edge) {
    mollify(x, c.mollifier_eps, kappa, b, grad_b, hess_b, with_hessian, result);
    return result;
  }
  result.value = kappa * b;
  result.gradient = kappa * grad_b;
  if (with_hessian) result.hessian = kappa * hess_b;
  return result;
}

}  // namespace

void BarrierTerm::add_energy(const PotentialPoint& at, double& sum) const {
  Eigen::Vector3d x[4];
  for (const ContactCandidate& c : at.candidates) {
    gather(at.positions, c.vertex, x);
    sum += barrier_of(c, x, model_.sim().d_hat, kappa_, false).value;
  }
}

void BarrierTerm::add_derivatives(const PotentialPoint& at, double scale,
                                  PotentialDerivatives& out) const {
  Eigen::Vector3d x[4];
  for (const ContactCandidate& c : at.candidates) {
    gather(at.positions, c.vertex, x);
    const Barrier b = barrier_of(c, x, model_.sim().d_hat, kappa_, out.hessian != nullptr);
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
  force.distance = std::sqrt(squared_distance(c, x));
  const Barrier b = barrier_of(c, x, d_hat, kappa_, false);
  force.force = -b.gradient;
  double m = 1.0;
  if (c.edge_edge) m = kernels::edge_edge_mollifier(x[0], x[1], x[2], x[3], c.mollifier_eps);
  force.magnitude = force.distance < d_hat && !c.near_at_rest
                        ? -kappa_ * m * kernels::barrier_first_derivative(force.distance, d_hat)
                        : 0.0;
  return force;
}

}  // namespace grip::solver
