#include "solver/potential/stencil.hpp"

#include <stdexcept>

namespace grip::solver {
namespace {

using StencilVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 24, 1>;
using StencilMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 24, 24>;

}  // namespace

Stencil::Stencil(const Model& model, const std::array<int, 4>& vertex) {
  const CollisionMesh& mesh = model.collision();
  int local[4];
  int dofs = 0;
  for (int i = 0; i < 4; ++i) {
    const BodyModel& body = model.bodies()[mesh.vertex_body[vertex[i]]];
    local[i] = -1;
    const int offset = body.kind->vertex_block(body.local, mesh.vertex_local[vertex[i]]);
    if (offset < 0) continue;
    for (int b = 0; b < blocks_; ++b) {
      if (block_offset_[b] == offset) local[i] = b;
    }
    if (local[i] < 0) {
      local[i] = blocks_;
      block_offset_[blocks_] = offset;
      block_size_[blocks_] = body.kind->block_size();
      dofs += block_size_[blocks_];
      ++blocks_;
    }
  }
  // A contact is a point and a triangle or two edges: on two bodies at most. More would overrun
  // the Jacobian's fixed capacity.
  if (dofs > kMaxDofs) throw std::logic_error("Stencil: a contact's vertices span over 24 DOFs");
  jacobian_.setZero(12, dofs);
  for (int i = 0; i < 4; ++i) {
    if (local[i] < 0) continue;
    int column = 0;
    for (int b = 0; b < local[i]; ++b) column += block_size_[b];
    const BodyModel& body = model.bodies()[mesh.vertex_body[vertex[i]]];
    jacobian_.block(3 * i, column, 3, block_size_[local[i]]) =
        body.kind->vertex_jacobian(body.local, mesh.vertex_local[vertex[i]]);
  }
}

int Stencil::global_dof(int local_dof) const {
  for (int b = 0; b < blocks_; ++b) {
    if (local_dof < block_size_[b]) return block_offset_[b] + local_dof;
    local_dof -= block_size_[b];
  }
  return -1;
}

void Stencil::scatter(const Vector12& g, const Matrix12& h, Eigen::VectorXd& gradient,
                      std::vector<Eigen::Triplet<double>>& hessian) const {
  const int n = static_cast<int>(jacobian_.cols());
  if (n == 0) return;
  const StencilVector local_g = jacobian_.transpose() * g;
  const StencilMatrix local_h = jacobian_.transpose() * h * jacobian_;
  for (int i = 0; i < n; ++i) {
    const int row = global_dof(i);
    gradient[row] += local_g[i];
    for (int j = 0; j < n; ++j) {
      const int col = global_dof(j);
      if (row >= col) hessian.emplace_back(row, col, local_h(i, j));
    }
  }
}

void Stencil::scatter_gradient(const Vector12& g, Eigen::VectorXd& gradient) const {
  const int n = static_cast<int>(jacobian_.cols());
  if (n == 0) return;
  const StencilVector local_g = jacobian_.transpose() * g;
  for (int i = 0; i < n; ++i) gradient[global_dof(i)] += local_g[i];
}

void Stencil::add_kinematic_force(const Matrix12& h, const Vertices& motion,
                                  const std::array<int, 4>& vertex, Eigen::VectorXd& force) const {
  Vector12 dk;
  for (int i = 0; i < 4; ++i) dk.segment<3>(3 * i) = motion.row(vertex[i]).transpose();
  if (dk.isZero() || jacobian_.cols() == 0) return;
  const StencilVector local = jacobian_.transpose() * (h * dk);
  for (int i = 0; i < local.size(); ++i) force[global_dof(i)] += local[i];
}

}  // namespace grip::solver
