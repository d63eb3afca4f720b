#include "solver/newton/incremental_potential.hpp"

#include "solver/kernels/affine_body.hpp"
#include "solver/kernels/barrier.hpp"
#include "solver/kernels/distance.hpp"
#include "solver/kernels/edge_edge_mollifier.hpp"
#include "solver/kernels/friction_potential.hpp"
#include "solver/kernels/neo_hookean.hpp"
#include "solver/kernels/psd_projection.hpp"

namespace grip::solver {
namespace {

using Vector12 = Eigen::Matrix<double, 12, 1>;
using Matrix12 = Eigen::Matrix<double, 12, 12>;
// A stencil of four vertices touches at most two affine bodies: 24 DOFs.
constexpr int kMaxStencilDofs = 24;
using StencilJacobian = Eigen::Matrix<double, 12, Eigen::Dynamic, 0, 12, kMaxStencilDofs>;
using StencilVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxStencilDofs, 1>;
using StencilMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxStencilDofs, kMaxStencilDofs>;

// Maps the 12 stacked positions of a contact's four collision vertices to the DOFs they depend
// on: 3 per FEM vertex, the 12 of an affine body (shared by its vertices), none for kinematic.
struct Stencil {
  int blocks = 0;
  int block_offset[4];  // first global DOF of each block
  int block_size[4];
  StencilJacobian jacobian;  // d(positions) / d(stencil DOFs)

  Stencil(const Model& model, const std::array<int, 4>& vertex) {
    const CollisionMesh& mesh = model.collision();
    int local[4];
    int dofs = 0;
    for (int i = 0; i < 4; ++i) {
      const BodyModel& body = model.bodies()[mesh.vertex_body[vertex[i]]];
      local[i] = -1;
      if (body.type == BodyType::kKinematic) continue;
      const int offset = body.type == BodyType::kFem
                             ? body.dof_offset + 3 * mesh.vertex_local[vertex[i]]
                             : body.dof_offset;
      for (int b = 0; b < blocks; ++b) {
        if (block_offset[b] == offset) local[i] = b;
      }
      if (local[i] < 0) {
        local[i] = blocks;
        block_offset[blocks] = offset;
        block_size[blocks] = body.type == BodyType::kFem ? 3 : 12;
        dofs += block_size[blocks];
        ++blocks;
      }
    }
    jacobian.setZero(12, dofs);
    for (int i = 0; i < 4; ++i) {
      if (local[i] < 0) continue;
      int column = 0;
      for (int b = 0; b < local[i]; ++b) column += block_size[b];
      const BodyModel& body = model.bodies()[mesh.vertex_body[vertex[i]]];
      if (body.type == BodyType::kFem) {
        jacobian.block<3, 3>(3 * i, column).setIdentity();
      } else {
        jacobian.block<3, 12>(3 * i, column) =
            kernels::affine_body_jacobian(body.rest.row(mesh.vertex_local[vertex[i]]));
      }
    }
  }

  int global_dof(int local_dof) const {
    for (int b = 0; b < blocks; ++b) {
      if (local_dof < block_size[b]) return block_offset[b] + local_dof;
      local_dof -= block_size[b];
    }
    return -1;
  }

  // Adds a position-space gradient and (PSD) Hessian to the global gradient and triplets.
  void scatter(const Vector12& g, const Matrix12& h, Eigen::VectorXd& gradient,
               std::vector<Eigen::Triplet<double>>& hessian) const {
    const int n = static_cast<int>(jacobian.cols());
    if (n == 0) return;
    const StencilVector local_g = jacobian.transpose() * g;
    const StencilMatrix local_h = jacobian.transpose() * h * jacobian;
    for (int i = 0; i < n; ++i) {
      const int row = global_dof(i);
      gradient[row] += local_g[i];
      for (int j = 0; j < n; ++j) {
        const int col = global_dof(j);
        if (row >= col) hessian.emplace_back(row, col, local_h(i, j));
      }
    }
  }
};

// Adds J^T H dk for the stencil's kinematic vertices' motion dk (zero rows elsewhere).
void add_kinematic_force(const Stencil& stencil, const Matrix12& h, const Vertices& motion,
                         const std::array<int, 4>& vertex, Eigen::VectorXd& force) {
  Vector12 dk;
  for (int i = 0; i < 4; ++i) dk.segment<3>(3 * i) = motion.row(vertex[i]).transpose();
  if (dk.isZero() || stencil.jacobian.cols() == 0) return;
  const StencilVector local = stencil.jacobian.transpose() * (h * dk);
  for (int i = 0; i < local.size(); ++i) force[stencil.global_dof(i)] += local[i];
}

void gather(const Vertices& positions, const std::array<int, 4>& vertex, Eigen::Vector3d x[4]) {
  for (int i = 0; i < 4; ++i) x[i] = positions.row(vertex[i]);
}

Vector12 stack(const Eigen::Vector3d x[4]) {
  Vector12 s;
  for (int i = 0; i < 4; ++i) s.segment<3>(3 * i) = x[i];
  return s;
}

double squared_distance(const ContactPair& pair, const Eigen::Vector3d x[4]) {
  return pair.edge_edge ? kernels::edge_edge_distance_sq(x[0], x[1], x[2], x[3])
                        : kernels::point_triangle_distance_sq(x[0], x[1], x[2], x[3]);
}

// kappa m b(d) and its derivatives in the four vertices' positions, with d = sqrt(s):
// db/ds = b'(d) / (2d), d2b/ds2 = (b''(d) - b'(d) / d) / (4 s).
struct Barrier {
  double value = 0.0;
  Vector12 gradient = Vector12::Zero();
  Matrix12 hessian = Matrix12::Zero();
};

Barrier barrier_of(const ContactPair& pair, const Eigen::Vector3d x[4], double d_hat, double kappa,
                   bool with_hessian) {
  Barrier result;
  const double s = squared_distance(pair, x);
  if (s >= d_hat * d_hat) return result;
  const double d = std::sqrt(s);
  const double b = kernels::barrier(d, d_hat);
  const double b1 = kernels::barrier_first_derivative(d, d_hat);
  const double db_ds = b1 / (2.0 * d);
  Vector12 grad_s;
  Matrix12 hess_s;
  if (pair.edge_edge) {
    grad_s = kernels::edge_edge_distance_sq_gradient(x[0], x[1], x[2], x[3]);
    if (with_hessian) hess_s = kernels::edge_edge_distance_sq_hessian(x[0], x[1], x[2], x[3]);
  } else {
    grad_s = kernels::point_triangle_distance_sq_gradient(x[0], x[1], x[2], x[3]);
    if (with_hessian) hess_s = kernels::point_triangle_distance_sq_hessian(x[0], x[1], x[2], x[3]);
  }
  const Vector12 grad_b = db_ds * grad_s;
  Matrix12 hess_b;
  if (with_hessian) {
    const double d2b_ds2 = (kernels::barrier_second_derivative(d, d_hat) - b1 / d) / (4.0 * s);
    hess_b = d2b_ds2 * grad_s * grad_s.transpose() + db_ds * hess_s;
  }
  double m = 1.0;
  if (pair.edge_edge) m = kernels::edge_edge_mollifier(x[0], x[1], x[2], x[3], pair.mollifier_eps);
  result.value = kappa * m * b;
  if (m == 1.0) {
    result.gradient = kappa * grad_b;
    if (with_hessian) result.hessian = kappa * hess_b;
    return result;
  }
  // The mollified product m b of nearly parallel edges.
  const Vector12 grad_m =
      kernels::edge_edge_mollifier_gradient(x[0], x[1], x[2], x[3], pair.mollifier_eps);
  result.gradient = kappa * (m * grad_b + b * grad_m);
  if (with_hessian) {
    const Matrix12 hess_m =
        kernels::edge_edge_mollifier_hessian(x[0], x[1], x[2], x[3], pair.mollifier_eps);
    result.hessian = kappa * (m * hess_b + grad_m * grad_b.transpose() +
                              grad_b * grad_m.transpose() + b * hess_m);
  }
  return result;
}

Vector12 tet_positions(const Eigen::VectorXd& q, int dof_offset, const FemTet& tet) {
  Vector12 x;
  for (int i = 0; i < 4; ++i) x.segment<3>(3 * i) = q.segment<3>(dof_offset + 3 * tet.vertices[i]);
  return x;
}

}  // namespace

void IncrementalPotential::begin_step(Eigen::VectorXd q_tilde, Vertices start_positions,
                                      double kappa) {
  q_tilde_ = std::move(q_tilde);
  start_ = std::move(start_positions);
  kappa_ = kappa;
  friction_.clear();
}

double IncrementalPotential::energy(const Eigen::VectorXd& q, const Vertices& positions,
                                    const std::vector<ContactPair>& pairs) const {
  const SimParameters& sim = model_.sim();
  const double h2 = sim.dt * sim.dt;
  double inertia = 0.0;
  double potential = 0.0;
  for (const BodyModel& body : model_.bodies()) {
    if (body.type == BodyType::kFem) {
      const int n = static_cast<int>(body.rest.rows());
      for (int v = 0; v < n; ++v) {
        const auto dx = q.segment<3>(body.dof_offset + 3 * v) -
                        q_tilde_.segment<3>(body.dof_offset + 3 * v);
        inertia += 0.5 * body.vertex_mass[v] * dx.squaredNorm();
      }
      for (const FemTet& tet : body.tets) {
        potential += kernels::tet_stable_neo_hookean_energy(tet_positions(q, body.dof_offset, tet),
                                                            tet.rest_shape_inverse,
                                                            tet.rest_volume, body.elasticity);
      }
    } else if (body.type == BodyType::kAffine) {
      const Vector12d qb = q.segment<12>(body.dof_offset);
      const Vector12d dq = qb - q_tilde_.segment<12>(body.dof_offset);
      inertia += 0.5 * dq.dot(body.mass_matrix * dq);
      potential += kernels::affine_body_orthogonality_energy(qb, body.orthogonality_stiffness,
                                                             body.volume);
    }
  }
  Eigen::Vector3d x[4];
  for (const ContactPair& pair : pairs) {
    gather(positions, pair.vertex, x);
    potential += barrier_of(pair, x, sim.d_hat, kappa_, false).value;
  }
  const double eps = sim.eps_v * sim.dt;
  for (const FrictionContact& c : friction_) {
    gather(positions, c.vertex, x);
    Eigen::Vector3d x0[4];
    gather(start_, c.vertex, x0);
    potential += kernels::friction_potential<4>(stack(x) - stack(x0), c.tangent_operator,
                                                c.mu_lambda, eps);
  }
  return inertia + h2 * potential;
}

void IncrementalPotential::derivatives(const Eigen::VectorXd& q, const Vertices& positions,
                                       const std::vector<ContactPair>& pairs,
                                       Eigen::VectorXd& gradient,
                                       std::vector<Eigen::Triplet<double>>& hessian,
                                       const Vertices* kinematic_motion,
                                       Eigen::VectorXd* kinematic_force) const {
  const SimParameters& sim = model_.sim();
  const double h2 = sim.dt * sim.dt;
  gradient.setZero(model_.dof_count());
  hessian.clear();
  if (kinematic_force) kinematic_force->setZero(model_.dof_count());
  for (const BodyModel& body : model_.bodies()) {
    if (body.type == BodyType::kFem) {
      const int n = static_cast<int>(body.rest.rows());
      for (int v = 0; v < n; ++v) {
        const int o = body.dof_offset + 3 * v;
        gradient.segment<3>(o) += body.vertex_mass[v] * (q.segment<3>(o) - q_tilde_.segment<3>(o));
        for (int k = 0; k < 3; ++k) hessian.emplace_back(o + k, o + k, body.vertex_mass[v]);
      }
      for (const FemTet& tet : body.tets) {
        const Vector12 x = tet_positions(q, body.dof_offset, tet);
        const Vector12 g = h2 * kernels::tet_stable_neo_hookean_gradient(
                                    x, tet.rest_shape_inverse, tet.rest_volume, body.elasticity);
        const Matrix12 h =
            h2 * kernels::tet_stable_neo_hookean_hessian(x, tet.rest_shape_inverse,
                                                         tet.rest_volume, body.elasticity, true);
        for (int a = 0; a < 4; ++a) {
          const int row = body.dof_offset + 3 * tet.vertices[a];
          gradient.segment<3>(row) += g.segment<3>(3 * a);
          for (int b = 0; b < 4; ++b) {
            const int col = body.dof_offset + 3 * tet.vertices[b];
            for (int i = 0; i < 3; ++i) {
              for (int j = 0; j < 3; ++j) {
                if (row + i >= col + j) hessian.emplace_back(row + i, col + j, h(3 * a + i, 3 * b + j));
              }
            }
          }
        }
      }
    } else if (body.type == BodyType::kAffine) {
      const int o = body.dof_offset;
      const Vector12d qb = q.segment<12>(o);
      const Vector12d g = body.mass_matrix * (qb - q_tilde_.segment<12>(o)) +
                          h2 * kernels::affine_body_orthogonality_gradient(
                                   qb, body.orthogonality_stiffness, body.volume);
      const Matrix12d h = body.mass_matrix + h2 * kernels::affine_body_orthogonality_hessian(
                                                      qb, body.orthogonality_stiffness,
                                                      body.volume, true);
      gradient.segment<12>(o) += g;
      for (int i = 0; i < 12; ++i) {
        for (int j = 0; j <= i; ++j) hessian.emplace_back(o + i, o + j, h(i, j));
      }
    }
  }
  Eigen::Vector3d x[4];
  for (const ContactPair& pair : pairs) {
    gather(positions, pair.vertex, x);
    const Barrier b = barrier_of(pair, x, sim.d_hat, kappa_, true);
    if (b.value == 0.0 && b.gradient.isZero()) continue;
    const Stencil stencil(model_, pair.vertex);
    const Matrix12 h = h2 * kernels::project_to_psd<12>(b.hessian);
    stencil.scatter(h2 * b.gradient, h, gradient, hessian);
    if (kinematic_motion) add_kinematic_force(stencil, h, *kinematic_motion, pair.vertex, *kinematic_force);
  }
  const double eps = sim.eps_v * sim.dt;
  for (const FrictionContact& c : friction_) {
    gather(positions, c.vertex, x);
    Eigen::Vector3d x0[4];
    gather(start_, c.vertex, x0);
    const Vector12 dx = stack(x) - stack(x0);
    const Stencil stencil(model_, c.vertex);
    const Matrix12 h =
        h2 * kernels::friction_potential_hessian<4>(dx, c.tangent_operator, c.mu_lambda, eps);
    stencil.scatter(
        h2 * kernels::friction_potential_gradient<4>(dx, c.tangent_operator, c.mu_lambda, eps), h,
        gradient, hessian);
    if (kinematic_motion) add_kinematic_force(stencil, h, *kinematic_motion, c.vertex, *kinematic_force);
  }
}

ContactForce IncrementalPotential::contact_force(const ContactPair& pair,
                                                 const Vertices& positions) const {
  const SimParameters& sim = model_.sim();
  Eigen::Vector3d x[4];
  gather(positions, pair.vertex, x);
  ContactForce force;
  force.distance = std::sqrt(squared_distance(pair, x));
  const Barrier b = barrier_of(pair, x, sim.d_hat, kappa_, false);
  force.force = -b.gradient;
  double m = 1.0;
  if (pair.edge_edge) m = kernels::edge_edge_mollifier(x[0], x[1], x[2], x[3], pair.mollifier_eps);
  force.magnitude =
      force.distance < sim.d_hat
          ? -kappa_ * m * kernels::barrier_first_derivative(force.distance, sim.d_hat)
          : 0.0;
  return force;
}

Eigen::Matrix<double, 12, 1> IncrementalPotential::friction_force(
    const FrictionContact& contact, const Vertices& positions) const {
  const SimParameters& sim = model_.sim();
  Eigen::Vector3d x[4];
  Eigen::Vector3d x0[4];
  gather(positions, contact.vertex, x);
  gather(start_, contact.vertex, x0);
  return -kernels::friction_potential_gradient<4>(stack(x) - stack(x0), contact.tangent_operator,
                                                  contact.mu_lambda, sim.eps_v * sim.dt);
}

}  // namespace grip::solver
