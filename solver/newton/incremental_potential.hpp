#pragma once
// The incremental potential of one implicit Euler step (IPC):
//   E(x) = 1/2 |x - x_tilde|_M^2 + h^2 [ elasticity + orthogonality + kappa sum_k b(d_k)
//                                        + sum_k mu lambda_k f0(|u_k|) ]
// where b is the log barrier on the unsquared distance d_k of each contact pair closer than
// d_hat, and the friction of each lagged contact acts on its tangential displacement u_k over
// the step. kappa is a stiffness (N/m) and lambda_k a force (N): at equilibrium M (x -
// x_tilde) / h^2 balances the physical forces. Derivatives are per element, projected to
// positive semi-definite before they are summed (projected Newton).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "solver/contact/candidates.hpp"
#include "solver/model.hpp"

namespace grip::solver {

// A contact frozen at the friction lag: its pair, mu * lambda (N) and its tangent operator.
struct FrictionContact {
  std::array<int, 4> vertex;
  bool edge_edge = false;
  double mu_lambda = 0.0;
  Eigen::Matrix<double, 12, 2> tangent_operator;
};

// What one contact pushes with at a configuration (for forces and the friction lag).
struct ContactForce {
  double distance = 0.0;
  double magnitude = 0.0;  // kappa m |b'(d)| (N), m the edge-edge mollifier (1 for points)
  Eigen::Matrix<double, 12, 1> force;  // on the four vertices, stacked (N)
};

class IncrementalPotential {
 public:
  explicit IncrementalPotential(const Model& model) : model_(model) {}

  // The step's constants: inertia target, start positions of the collision vertices and the
  // barrier stiffness. Clears the friction contacts.
  void begin_step(Eigen::VectorXd q_tilde, Vertices start_positions, double kappa);
  // The contacts frozen at this friction lag iteration.
  void set_friction(std::vector<FrictionContact> friction) { friction_ = std::move(friction); }

  // positions: the collision vertices at q (kinematic ones where the step has moved them).
  double energy(const Eigen::VectorXd& q, const Vertices& positions,
                const std::vector<ContactPair>& pairs) const;

  // The gradient, and the lower triangle of the PSD-projected Hessian as triplets. With
  // `kinematic_motion` (the motion still to come of each collision vertex, non-zero only at
  // kinematic ones), also the DOF-space force H_fk dk their motion adds to first order, so that
  // a Newton step can make room for a kinematic body before it arrives.
  void derivatives(const Eigen::VectorXd& q, const Vertices& positions,
                   const std::vector<ContactPair>& pairs, Eigen::VectorXd& gradient,
                   std::vector<Eigen::Triplet<double>>& hessian,
                   const Vertices* kinematic_motion = nullptr,
                   Eigen::VectorXd* kinematic_force = nullptr) const;

  // The barrier force of one pair, or nothing (magnitude 0) beyond d_hat.
  ContactForce contact_force(const ContactPair& pair, const Vertices& positions) const;

  // The friction force (N, on the four vertices) of a lagged contact at `positions`.
  Eigen::Matrix<double, 12, 1> friction_force(const FrictionContact& contact,
                                              const Vertices& positions) const;

  const std::vector<FrictionContact>& friction() const { return friction_; }

 private:
  const Model& model_;
  Eigen::VectorXd q_tilde_;
  Vertices start_;
  double kappa_ = 0.0;
  std::vector<FrictionContact> friction_;
};

}  // namespace grip::solver
