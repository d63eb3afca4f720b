#pragma once
// The DOFs a contact's four collision vertices move with: 3 per FEM vertex, the 12 of an affine
// body (shared by its vertices), none for a kinematic one. A stencil maps a position-space
// gradient and Hessian (12 entries) to those DOFs and scatters them into the global system.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <vector>

#include "solver/model/model.hpp"

namespace grip::solver {

class Stencil {
 public:
  using Vector12 = Eigen::Matrix<double, 12, 1>;
  using Matrix12 = Eigen::Matrix<double, 12, 12>;

  Stencil(const Model& model, const std::array<int, 4>& vertex);

  // Adds a position-space gradient and (PSD) Hessian to the global gradient and triplets.
  void scatter(const Vector12& g, const Matrix12& h, Eigen::VectorXd& gradient,
               std::vector<Eigen::Triplet<double>>& hessian) const;
  // The gradient alone, as scatter() adds it.
  void scatter_gradient(const Vector12& g, Eigen::VectorXd& gradient) const;
  // Adds J^T h dk for the motion dk of the stencil's kinematic vertices (zero rows elsewhere).
  void add_kinematic_force(const Matrix12& h, const Vertices& motion,
                           const std::array<int, 4>& vertex, Eigen::VectorXd& force) const;

 private:
  // A stencil of four vertices touches at most two affine bodies: 24 DOFs.
  static constexpr int kMaxDofs = 24;
  using Jacobian = Eigen::Matrix<double, 12, Eigen::Dynamic, 0, 12, kMaxDofs>;

  int global_dof(int local_dof) const;

  int blocks_ = 0;
  int block_offset_[4];  // first global DOF of each block
  int block_size_[4];
  Jacobian jacobian_;  // d(positions) / d(stencil DOFs)
};

}  // namespace grip::solver
