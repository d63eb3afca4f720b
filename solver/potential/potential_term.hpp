#pragma once
// One term of the incremental potential (inertia, elasticity, barrier, friction), in the manner
// of ipc-toolkit's potentials: each adds its value, and its gradient and PSD-projected Hessian
// in DOF space, at a point of the Newton solve. Terms add into running sums rather than return
// their own, so the summation order (and every bit of the result) does not depend on how the
// potential is split into terms.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "solver/contact/candidates.hpp"
#include "solver/scene/scene.hpp"

namespace grip::solver {

// Where the terms are evaluated: the DOFs, the collision vertices' positions there (kinematic
// ones where the step has moved them) and the contact candidates near those positions.
struct PotentialPoint {
  const Eigen::VectorXd& q;
  const Vertices& positions;
  const std::vector<ContactCandidate>& candidates;
};

// Where derivatives are added. With `kinematic_motion` (the motion still to come of each
// collision vertex, non-zero only at kinematic ones), contact terms also add the DOF-space force
// H_fk dk that this motion causes to first order, so that a Newton step can make room for a
// kinematic body before it arrives.
struct PotentialDerivatives {
  Eigen::VectorXd& gradient;
  // Lower triangle; null: the gradient alone (a convergence test needs no Hessian).
  std::vector<Eigen::Triplet<double>>* hessian;
  const Vertices* kinematic_motion = nullptr;
  Eigen::VectorXd* kinematic_force = nullptr;
  // Contact Hessians projected to PSD one by one (else added as they are).
  bool project_contacts = true;
};

class PotentialTerm {
 public:
  virtual ~PotentialTerm() = default;
  // Adds the term's value to `sum`.
  virtual void add_energy(const PotentialPoint& at, double& sum) const = 0;
  // Adds `scale` times the term's gradient and (unless out.hessian is null) PSD-projected
  // Hessian.
  virtual void add_derivatives(const PotentialPoint& at, double scale,
                               PotentialDerivatives& out) const = 0;
};

}  // namespace grip::solver
