#pragma once
// The contact barrier: kappa sum_k m_k b(d_k) over the contact candidates closer than d_hat,
// with b IPC's log barrier on the unsquared distance and m_k the parallel-edge mollifier of an
// edge-edge pair (1 for point-triangle). kappa is a stiffness (N/m).
#include <Eigen/Core>

#include "solver/model/model.hpp"
#include "solver/potential/potential_term.hpp"

namespace grip::solver {

// What one contact pushes with at a configuration (for forces and the friction lag).
struct ContactForce {
  double distance = 0.0;
  double magnitude = 0.0;  // kappa m |b'(d)| (N), m the edge-edge mollifier (1 for points)
  Eigen::Matrix<double, 12, 1> force;  // on the four vertices, stacked (N)
};

class BarrierTerm : public PotentialTerm {
 public:
  explicit BarrierTerm(const Model& model) : model_(model) {}
  void set_kappa(double kappa) { kappa_ = kappa; }

  void add_energy(const PotentialPoint& at, double& sum) const override;
  void add_derivatives(const PotentialPoint& at, double scale,
                       PotentialDerivatives& out) const override;

  // The barrier force of one candidate, or nothing (magnitude 0) beyond d_hat.
  ContactForce contact_force(const ContactCandidate& candidate, const Vertices& positions) const;

 private:
  const Model& model_;
  double kappa_ = 0.0;
};

}  // namespace grip::solver
