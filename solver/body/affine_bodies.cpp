#include "solver/body/affine_bodies.hpp"

#include <Eigen/LU>
#include <algorithm>

#include "solver/kernels/affine_body.hpp"
#include "solver/kernels/psd_projection.hpp"

namespace grip::solver {
namespace {

// Mass, first and second moments of a closed surface of unit density, by the divergence
// theorem: the signed tetrahedra from the origin to each outward triangle.
struct VolumeMoments {
  double volume = 0.0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();   // integral of x
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();  // integral of x x^T
};

VolumeMoments volume_moments(const Vertices& v, const Triangles& f) {
  VolumeMoments m;
  for (Eigen::Index t = 0; t < f.rows(); ++t) {
    const Eigen::Vector3d a = v.row(f(t, 0)), b = v.row(f(t, 1)), c = v.row(f(t, 2));
    const double vol = a.dot(b.cross(c)) / 6.0;
    const Eigen::Vector3d s = a + b + c;
    m.volume += vol;
    m.first += vol * s / 4.0;
    m.second += vol / 20.0 *
                (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
  }
  return m;
}

// M = integral of rho J^T J over the body, J(x) = J0 + sum_k x_k J_k linear in the rest point,
// written through the kernel's Jacobian so it holds for its DOF layout.
Matrix12d integrated_mass_matrix(double density, const VolumeMoments& m) {
  using Jacobian = Eigen::Matrix<double, 3, 12>;
  const Jacobian j0 = kernels::affine_body_jacobian(Eigen::Vector3d::Zero());
  Jacobian jk[3];
  for (int k = 0; k < 3; ++k) jk[k] = kernels::affine_body_jacobian(Eigen::Vector3d::Unit(k)) - j0;
  Matrix12d mass = m.volume * j0.transpose() * j0;
  for (int k = 0; k < 3; ++k) {
    mass += m.first[k] * (j0.transpose() * jk[k] + jk[k].transpose() * j0);
    for (int l = 0; l < 3; ++l) mass += m.second(k, l) * jk[k].transpose() * jk[l];
  }
  return density * mass;
}

}  // namespace

// Rest vertices about the centre of mass, volume, mass matrix, orthogonality stiffness.
void AffineBodies::build(const BodyDescription& description) {
  if (description.material.density <= 0) invalid_body(description, "needs density > 0");
  if (description.orthogonality_stiffness <= 0) {
    invalid_body(description, "needs orthogonality_stiffness > 0");
  }
  const VolumeMoments raw = volume_moments(description.vertices, description.triangles);
  if (!(raw.volume > 0)) {
    invalid_body(description, "encloses no positive volume (is its surface closed and outward?)");
  }
  const Eigen::Vector3d offset = raw.first / raw.volume;
  const Vertices rest = description.vertices.rowwise() - offset.transpose();
  const VolumeMoments centred = volume_moments(rest, description.triangles);
  for (Eigen::Index v = 0; v < rest.rows(); ++v) rest_.push_back(rest.row(v).transpose());
  vertex_begin_.push_back(static_cast<int>(rest_.size()));
  center_of_mass_offset_.push_back(offset);
  volume_.push_back(centred.volume);
  mass_matrix_.push_back(integrated_mass_matrix(description.material.density, centred));
  mass_matrix_inverse_.push_back(mass_matrix_.back().inverse());
  density_.push_back(description.material.density);
  orthogonality_stiffness_.push_back(description.orthogonality_stiffness);
}

void AffineBodies::set_pose(int i, const Pose& pose, Eigen::VectorXd& dofs) const {
  const Eigen::Matrix3d r = pose.rotation.normalized().toRotationMatrix();
  const Eigen::Vector3d com = pose.position + r * center_of_mass_offset_[i];
  dofs.segment<12>(dof_offset(i)) = kernels::affine_body_dofs(r, com);
}

void AffineBodies::initial_state(int i, const BodyDescription& description, State& state) const {
  set_pose(i, description.pose, state.q);
  const Eigen::Matrix3d r = description.pose.rotation.normalized().toRotationMatrix();
  // dA/dt = [omega]x A; q is linear in (A, p), so the same map gives the DOF velocity.
  const Eigen::Vector3d& w = description.angular_velocity;
  Eigen::Matrix3d omega_cross;
  omega_cross << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  state.v.segment<12>(dof_offset(i)) =
      kernels::affine_body_dofs(omega_cross * r, description.velocity);
}

void AffineBodies::place(int i, const Eigen::Isometry3d& motion, State& state) const {
  const Eigen::Matrix3d r = motion.linear();
  const Eigen::Vector3d t = motion.translation();
  const int o = dof_offset(i);
  const Vector12d qb = state.q.segment<12>(o), vb = state.v.segment<12>(o);
  state.q.segment<12>(o) =
      kernels::affine_body_dofs(r * kernels::affine_body_matrix(qb), r * qb.segment<3>(0) + t);
  state.v.segment<12>(o) =
      kernels::affine_body_dofs(r * kernels::affine_body_matrix(vb), r * vb.segment<3>(0));
}

// A fixture holds the whole body.
std::vector<int> AffineBodies::held_dofs(int i, const State& /*state*/) const {
  std::vector<int> dofs;
  for (int d = 0; d < dof_count(i); ++d) dofs.push_back(dof_offset(i) + d);
  return dofs;
}

Eigen::Vector3d AffineBodies::center_of_mass(int i, const State& state) const {
  return state.q.segment<3>(dof_offset(i));
}

Eigen::Vector3d AffineBodies::center_of_mass_velocity(int i, const State& state) const {
  return state.v.segment<3>(dof_offset(i));
}

// The rotation nearest the body's affine matrix.
Eigen::Matrix3d AffineBodies::rotation(int i, const State& state) const {
  return nearest_rotation(kernels::affine_body_matrix(state.q.segment<12>(dof_offset(i))));
}

void AffineBodies::vertex_positions(int i, const Eigen::VectorXd& q, const Pose& /*pose*/,
                                    std::span<const int> vertices, Vertices& out,
                                    Eigen::Index first_row) const {
  for (std::size_t k = 0; k < vertices.size(); ++k) {
    out.row(first_row + static_cast<Eigen::Index>(k)) =
        kernels::affine_body_position(q.segment<12>(dof_offset(i)), rest_vertex(i, vertices[k]));
  }
}

VertexJacobian AffineBodies::vertex_jacobian(int i, int v) const {
  return kernels::affine_body_jacobian(rest_vertex(i, v));
}

double AffineBodies::max_displacement(int i, const Eigen::VectorXd& dq) const {
  double largest = 0.0;
  const Vector12d db = dq.segment<12>(dof_offset(i));
  for (int v = 0; v < vertex_count(i); ++v) {
    const Eigen::Vector3d rest = rest_vertex(i, v);
    largest = std::max(largest, (kernels::affine_body_jacobian(rest) * db).norm());
  }
  return largest;
}

// h^2 M^-1 f_gravity added to the body's inertia target.
void AffineBodies::add_gravity(int i, const Eigen::Vector3d& gravity, double h,
                               Eigen::VectorXd& q_tilde) const {
  const Vector12d force = density_[i] * volume_[i] *
                          kernels::affine_body_jacobian(Eigen::Vector3d::Zero()).transpose() *
                          gravity;
  q_tilde.segment<12>(dof_offset(i)) += h * h * mass_matrix_inverse_[i] * force;
}

void AffineBodies::add_inertia_energy(int i, const Eigen::VectorXd& q,
                                      const Eigen::VectorXd& q_tilde, double& sum) const {
  const Vector12d dq = q.segment<12>(dof_offset(i)) - q_tilde.segment<12>(dof_offset(i));
  sum += 0.5 * dq.dot(mass_matrix_[i] * dq);
}

void AffineBodies::add_inertia_derivatives(int i, const Eigen::VectorXd& q,
                                           const Eigen::VectorXd& q_tilde, double scale,
                                           Eigen::VectorXd& gradient, Triplets* hessian) const {
  const int o = dof_offset(i);
  const Vector12d qb = q.segment<12>(o);
  gradient.segment<12>(o) += scale * (mass_matrix_[i] * (qb - q_tilde.segment<12>(o)));
  if (hessian) add_mass_triplets(i, scale, *hessian);
}

void AffineBodies::add_mass_triplets(int i, double s, Triplets& hessian) const {
  const int o = dof_offset(i);
  for (int r = 0; r < 12; ++r) {
    for (int c = 0; c <= r; ++c) hessian.emplace_back(o + r, o + c, s * mass_matrix_[i](r, c));
  }
}

void AffineBodies::add_elastic_energy(int i, const Eigen::VectorXd& q, double& sum) const {
  sum += kernels::affine_body_orthogonality_energy(q.segment<12>(dof_offset(i)),
                                                   orthogonality_stiffness_[i], volume_[i]);
}

void AffineBodies::add_elastic_derivatives(int i, const Eigen::VectorXd& q, double scale,
                                           const StepDamping* /*damping*/,
                                           Eigen::VectorXd& gradient, Triplets* hessian) const {
  const int o = dof_offset(i);
  const Vector12d qb = q.segment<12>(o);
  gradient.segment<12>(o) += scale * kernels::affine_body_orthogonality_gradient(
                                         qb, orthogonality_stiffness_[i], volume_[i]);
  if (!hessian) return;
  // The 9x9 block in the rows of A, projected; p's rows and columns are zero.
  Matrix12d h = Matrix12d::Zero();
  h.block<9, 9>(3, 3) = kernels::project_to_psd<9>(
      kernels::affine_body_orthogonality_block(qb, orthogonality_stiffness_[i], volume_[i]));
  h *= scale;
  for (int r = 0; r < 12; ++r) {
    for (int c = 0; c <= r; ++c) hessian->emplace_back(o + r, o + c, h(r, c));
  }
}

}  // namespace grip::solver
