#pragma once
// Lagged friction: sum_k mu lambda_k f0(|u_k|) over the contacts frozen at the friction lag,
// with u_k the tangential displacement of contact k over the step (from the step's start
// positions) and f0 IPC's smoothed transition from static to dynamic friction at eps_v dt.
#include <Eigen/Core>
#include <array>
#include <vector>

#include "solver/model/model.hpp"
#include "solver/potential/potential_term.hpp"

namespace grip::solver {

// A contact frozen at the friction lag: its stencil, mu * lambda (N) and its tangent operator.
struct FrictionContact {
  std::array<int, 4> vertex;
  bool edge_edge = false;
  double mu_lambda = 0.0;
  Eigen::Matrix<double, 12, 2> tangent_operator;
};

class FrictionTerm : public PotentialTerm {
 public:
  explicit FrictionTerm(const Model& model) : model_(model) {}
  // The step's start positions of the collision vertices and its length h (friction turns
  // static below eps_v h of tangential displacement); clears the contacts.
  void begin_step(Vertices start_positions, double h);
  void set_contacts(std::vector<FrictionContact> contacts) { contacts_ = std::move(contacts); }
  const std::vector<FrictionContact>& contacts() const { return contacts_; }

  void add_energy(const PotentialPoint& at, double& sum) const override;
  void add_derivatives(const PotentialPoint& at, double scale,
                       PotentialDerivatives& out) const override;

  // The friction force (N, on the four vertices) of a lagged contact at `positions`.
  Eigen::Matrix<double, 12, 1> force(const FrictionContact& contact,
                                     const Vertices& positions) const;

 private:
  // The contact's stacked vertex displacements from the step's start.
  Eigen::Matrix<double, 12, 1> displacement(const FrictionContact& contact,
                                            const Vertices& positions) const;

  const Model& model_;
  double eps_ = 0.0;  // m, eps_v h
  Vertices start_;
  std::vector<FrictionContact> contacts_;
};

}  // namespace grip::solver
