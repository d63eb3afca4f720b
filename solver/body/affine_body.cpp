#include "solver/body/affine_body.hpp"

#include <Eigen/LU>
#include <algorithm>

#include "solver/body/body.hpp"
#include "solver/kernels/affine_body.hpp"

namespace grip::solver::affine {
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
Matrix12d mass_matrix(double density, const VolumeMoments& m) {
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

void build(const BodyDescription& description, BodyModel& body) {
  if (description.material.density <= 0) invalid_body(description, "needs density > 0");
  if (description.orthogonality_stiffness <= 0) {
    invalid_body(description, "needs orthogonality_stiffness > 0");
  }
  const VolumeMoments raw = volume_moments(description.vertices, description.triangles);
  if (!(raw.volume > 0)) {
    invalid_body(description, "encloses no positive volume (is its surface closed and outward?)");
  }
  body.center_of_mass_offset = raw.first / raw.volume;
  body.rest = description.vertices.rowwise() - body.center_of_mass_offset.transpose();
  const VolumeMoments centred = volume_moments(body.rest, description.triangles);
  body.volume = centred.volume;
  body.mass_matrix = mass_matrix(description.material.density, centred);
  body.mass_matrix_inverse = body.mass_matrix.inverse();
  body.orthogonality_stiffness = description.orthogonality_stiffness;
  body.dof_count = 12;
}

void set_pose(const BodyModel& body, const Pose& pose, Eigen::VectorXd& q) {
  const Eigen::Matrix3d r = pose.rotation.normalized().toRotationMatrix();
  const Eigen::Vector3d com = pose.position + r * body.center_of_mass_offset;
  q.segment<12>(body.dof_offset) = kernels::affine_body_dofs(r, com);
}

void initial_state(const BodyModel& body, const BodyDescription& description, Eigen::VectorXd& q,
                   Eigen::VectorXd& v) {
  set_pose(body, description.pose, q);
  const Eigen::Matrix3d r = description.pose.rotation.normalized().toRotationMatrix();
  // dA/dt = [omega]x A; q is linear in (A, p), so the same map gives the DOF velocity.
  const Eigen::Vector3d& w = description.angular_velocity;
  Eigen::Matrix3d omega_cross;
  omega_cross << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  v.segment<12>(body.dof_offset) = kernels::affine_body_dofs(omega_cross * r, description.velocity);
}

void place(const BodyModel& body, const Eigen::Isometry3d& motion, Eigen::VectorXd& q,
           Eigen::VectorXd& v) {
  const Eigen::Matrix3d r = motion.linear();
  const Eigen::Vector3d t = motion.translation();
  const Vector12d qb = q.segment<12>(body.dof_offset), vb = v.segment<12>(body.dof_offset);
  q.segment<12>(body.dof_offset) =
      kernels::affine_body_dofs(r * kernels::affine_body_matrix(qb), r * qb.segment<3>(0) + t);
  v.segment<12>(body.dof_offset) =
      kernels::affine_body_dofs(r * kernels::affine_body_matrix(vb), r * vb.segment<3>(0));
}

Eigen::Vector3d vertex_position(const BodyModel& body, const Eigen::VectorXd& q, int vertex) {
  return kernels::affine_body_position(q.segment<12>(body.dof_offset),
                                       body.rest.row(vertex).transpose());
}

Eigen::Matrix<double, 3, 12> vertex_jacobian(const BodyModel& body, int vertex) {
  return kernels::affine_body_jacobian(body.rest.row(vertex));
}

double max_displacement(const BodyModel& body, const Eigen::VectorXd& dq) {
  double largest = 0.0;
  const Vector12d db = dq.segment<12>(body.dof_offset);
  for (Eigen::Index i = 0; i < body.rest.rows(); ++i) {
    const Eigen::Vector3d rest = body.rest.row(i);
    largest = std::max(largest, (kernels::affine_body_jacobian(rest) * db).norm());
  }
  return largest;
}

void add_gravity(const BodyModel& body, const Eigen::Vector3d& gravity, double h,
                 Eigen::VectorXd& q_tilde) {
  const Vector12d force = body.material.density * body.volume *
                          kernels::affine_body_jacobian(Eigen::Vector3d::Zero()).transpose() *
                          gravity;
  q_tilde.segment<12>(body.dof_offset) += h * h * body.mass_matrix_inverse * force;
}

Eigen::Matrix3d rotation(const BodyModel& body, const Eigen::VectorXd& q) {
  return nearest_rotation(kernels::affine_body_matrix(q.segment<12>(body.dof_offset)));
}

void add_inertia_energy(const BodyModel& body, const Eigen::VectorXd& q,
                        const Eigen::VectorXd& q_tilde, double& sum) {
  const Vector12d dq = q.segment<12>(body.dof_offset) - q_tilde.segment<12>(body.dof_offset);
  sum += 0.5 * dq.dot(body.mass_matrix * dq);
}

void add_inertia_derivatives(const BodyModel& body, const Eigen::VectorXd& q,
                             const Eigen::VectorXd& q_tilde, double scale,
                             Eigen::VectorXd& gradient,
                             std::vector<Eigen::Triplet<double>>* hessian) {
  const int o = body.dof_offset;
  const Vector12d qb = q.segment<12>(o);
  gradient.segment<12>(o) += scale * (body.mass_matrix * (qb - q_tilde.segment<12>(o)));
  if (!hessian) return;
  for (int i = 0; i < 12; ++i) {
    for (int j = 0; j <= i; ++j)
      hessian->emplace_back(o + i, o + j, scale * body.mass_matrix(i, j));
  }
}

void add_elastic_energy(const BodyModel& body, const Eigen::VectorXd& q, double& sum) {
  sum += kernels::affine_body_orthogonality_energy(q.segment<12>(body.dof_offset),
                                                   body.orthogonality_stiffness, body.volume);
}

void add_elastic_derivatives(const BodyModel& body, const Eigen::VectorXd& q, double scale,
                             Eigen::VectorXd& gradient,
                             std::vector<Eigen::Triplet<double>>* hessian) {
  const int o = body.dof_offset;
  const Vector12d qb = q.segment<12>(o);
  gradient.segment<12>(o) += scale * kernels::affine_body_orthogonality_gradient(
                                         qb, body.orthogonality_stiffness, body.volume);
  if (!hessian) return;
  const Matrix12d h = scale * kernels::affine_body_orthogonality_hessian(
                                  qb, body.orthogonality_stiffness, body.volume, true);
  for (int i = 0; i < 12; ++i) {
    for (int j = 0; j <= i; ++j) hessian->emplace_back(o + i, o + j, h(i, j));
  }
}

}  // namespace grip::solver::affine
