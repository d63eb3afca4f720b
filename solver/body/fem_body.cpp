#include "solver/body/fem_body.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "solver/body/body.hpp"
#include "solver/kernels/neo_hookean.hpp"

namespace grip::solver::fem {
namespace {

using Vector12 = Eigen::Matrix<double, 12, 1>;
using Matrix12 = Eigen::Matrix<double, 12, 12>;

Vector12 tet_positions(const Eigen::VectorXd& q, int dof_offset, const FemTet& tet) {
  Vector12 x;
  for (int i = 0; i < 4; ++i) x.segment<3>(3 * i) = q.segment<3>(dof_offset + 3 * tet.vertices[i]);
  return x;
}

// Scatters one tet's 12-vector gradient into the DOF-space gradient, and its 12x12 Hessian
// into the lower-triangle triplets.
void add_tet_gradient(const BodyModel& body, const FemTet& tet, const Vector12& g,
                      Eigen::VectorXd& gradient) {
  for (int a = 0; a < 4; ++a) {
    gradient.segment<3>(body.dof_offset + 3 * tet.vertices[a]) += g.segment<3>(3 * a);
  }
}

// The 78 lower-triangle entries of a tet's Hessian (its four vertices are distinct), written
// through a pointer: with emplace_back, the vector's capacity test and the store of its end after
// every entry were the most sampled instructions of the FEM derivatives.
void add_tet_hessian(const BodyModel& body, const FemTet& tet, const Matrix12& h,
                     std::vector<Eigen::Triplet<double>>& hessian) {
  constexpr std::size_t kLowerEntries = 4 * 6 + 6 * 9;
  const std::size_t first = hessian.size();
  hessian.resize(first + kLowerEntries);
  Eigen::Triplet<double>* out = hessian.data() + first;
  for (int a = 0; a < 4; ++a) {
    const int row = body.dof_offset + 3 * tet.vertices[a];
    for (int b = 0; b < 4; ++b) {
      const int col = body.dof_offset + 3 * tet.vertices[b];
      if (row < col) continue;
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
          if (row + i >= col + j) *out++ = {row + i, col + j, h(3 * a + i, 3 * b + j)};
        }
      }
    }
  }
}

FemTet rest_tet(const BodyDescription& description, const BodyModel& body, Eigen::Index t) {
  FemTet tet;
  for (int i = 0; i < 4; ++i) tet.vertices[i] = description.tets(t, i);
  const Eigen::Vector3d x0 = body.rest.row(tet.vertices[0]), x1 = body.rest.row(tet.vertices[1]),
                        x2 = body.rest.row(tet.vertices[2]), x3 = body.rest.row(tet.vertices[3]);
  tet.rest_volume = kernels::tet_rest_volume(x0, x1, x2, x3);
  if (!(tet.rest_volume > 0)) {
    invalid_body(description, "tetrahedron " + std::to_string(t) +
                                  " is inverted or flat at rest (volume " +
                                  std::to_string(tet.rest_volume) + " m^3)");
  }
  tet.rest_shape_inverse = kernels::tet_rest_shape_inverse(x0, x1, x2, x3);
  return tet;
}

void check(const BodyDescription& description) {
  if (description.tets.rows() == 0) invalid_body(description, "is FEM but has no tetrahedra");
  if (description.tets.minCoeff() < 0 ||
      description.tets.maxCoeff() >= description.vertices.rows()) {
    invalid_body(description, "has a tetrahedron index outside its vertices");
  }
  const Material& m = description.material;
  if (m.density <= 0 || m.youngs <= 0 || m.poisson <= -1 || m.poisson >= 0.5) {
    invalid_body(description, "needs density > 0, youngs > 0 and -1 < poisson < 0.5");
  }
  if (!(m.damping >= 0 && std::isfinite(m.damping))) {
    invalid_body(description, "needs a finite damping >= 0 (s)");
  }
}

}  // namespace

void build(const BodyDescription& description, BodyModel& body) {
  check(description);
  const Eigen::Matrix3d r = description.pose.rotation.normalized().toRotationMatrix();
  body.rest =
      (description.vertices * r.transpose()).rowwise() + description.pose.position.transpose();
  body.vertex_mass = Eigen::VectorXd::Zero(body.rest.rows());
  body.elasticity = kernels::stable_neo_hookean_parameters(description.material.youngs,
                                                           description.material.poisson);
  for (Eigen::Index t = 0; t < description.tets.rows(); ++t) {
    const FemTet tet = rest_tet(description, body, t);
    for (int i = 0; i < 4; ++i) {
      body.vertex_mass[tet.vertices[i]] += description.material.density * tet.rest_volume / 4.0;
    }
    body.tets.push_back(tet);
  }
  if ((body.vertex_mass.array() <= 0).any()) {
    invalid_body(description, "has a vertex that belongs to no tetrahedron");
  }
  body.dof_count = 3 * static_cast<int>(body.rest.rows());
}

void initial_state(const BodyModel& body, const BodyDescription& description, Eigen::VectorXd& q,
                   Eigen::VectorXd& v) {
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  for (Eigen::Index i = 0; i < body.rest.rows(); ++i) {
    com += body.vertex_mass[i] * body.rest.row(i).transpose();
  }
  com /= body.vertex_mass.sum();
  for (Eigen::Index i = 0; i < body.rest.rows(); ++i) {
    const Eigen::Vector3d x = body.rest.row(i);
    q.segment<3>(body.dof_offset + 3 * i) = x;
    v.segment<3>(body.dof_offset + 3 * i) =
        description.velocity + description.angular_velocity.cross(x - com);
  }
}

void place(const BodyModel& body, const Eigen::Isometry3d& motion, Eigen::VectorXd& q,
           Eigen::VectorXd& v) {
  const Eigen::Matrix3d r = motion.linear();
  const Eigen::Vector3d t = motion.translation();
  for (Eigen::Index i = 0; i < body.rest.rows(); ++i) {
    const int o = body.dof_offset + 3 * static_cast<int>(i);
    q.segment<3>(o) = r * q.segment<3>(o) + t;
    v.segment<3>(o) = r * v.segment<3>(o);
  }
}

double max_displacement(const BodyModel& body, const Eigen::VectorXd& dq) {
  double largest = 0.0;
  for (Eigen::Index i = 0; i < body.rest.rows(); ++i) {
    largest = std::max(largest, dq.segment<3>(body.dof_offset + 3 * i).norm());
  }
  return largest;
}

void add_gravity(const BodyModel& body, const Eigen::Vector3d& gravity, double h,
                 Eigen::VectorXd& q_tilde) {
  for (Eigen::Index i = 0; i < body.rest.rows(); ++i) {
    q_tilde.segment<3>(body.dof_offset + 3 * i) += h * h * gravity;
  }
}

Eigen::Vector3d mass_weighted_mean(const BodyModel& body, const Eigen::VectorXd& values) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (Eigen::Index i = 0; i < body.rest.rows(); ++i) {
    sum += body.vertex_mass[i] * values.segment<3>(body.dof_offset + 3 * i);
  }
  return sum / body.vertex_mass.sum();
}

Eigen::Matrix3d rotation(const BodyModel& body, const Eigen::VectorXd& q) {
  const double mass = body.vertex_mass.sum();
  Eigen::Vector3d rest_com = Eigen::Vector3d::Zero();
  for (Eigen::Index i = 0; i < body.rest.rows(); ++i) {
    rest_com += body.vertex_mass[i] * body.rest.row(i).transpose();
  }
  rest_com /= mass;
  const Eigen::Vector3d com = mass_weighted_mean(body, q);
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (Eigen::Index i = 0; i < body.rest.rows(); ++i) {
    covariance += body.vertex_mass[i] * (q.segment<3>(body.dof_offset + 3 * i) - com) *
                  (body.rest.row(i).transpose() - rest_com).transpose();
  }
  return nearest_rotation(covariance);
}

double min_volume_ratio(const BodyModel& body, const Eigen::VectorXd& q) {
  double ratio = 1.0;
  for (const FemTet& tet : body.tets) {
    const Vector12 x = tet_positions(q, body.dof_offset, tet);
    ratio = std::min(ratio, kernels::deformation_gradient(x, tet.rest_shape_inverse).determinant());
  }
  return ratio;
}

void add_inertia_energy(const BodyModel& body, const Eigen::VectorXd& q,
                        const Eigen::VectorXd& q_tilde, double& sum) {
  const int n = static_cast<int>(body.rest.rows());
  for (int i = 0; i < n; ++i) {
    const auto dx =
        q.segment<3>(body.dof_offset + 3 * i) - q_tilde.segment<3>(body.dof_offset + 3 * i);
    sum += 0.5 * body.vertex_mass[i] * dx.squaredNorm();
  }
}

void add_inertia_derivatives(const BodyModel& body, const Eigen::VectorXd& q,
                             const Eigen::VectorXd& q_tilde, double scale,
                             Eigen::VectorXd& gradient,
                             std::vector<Eigen::Triplet<double>>* hessian) {
  const int n = static_cast<int>(body.rest.rows());
  for (int i = 0; i < n; ++i) {
    const int o = body.dof_offset + 3 * i;
    const double mass = scale * body.vertex_mass[i];
    gradient.segment<3>(o) += mass * (q.segment<3>(o) - q_tilde.segment<3>(o));
    if (!hessian) continue;
    for (int k = 0; k < 3; ++k) hessian->emplace_back(o + k, o + k, mass);
  }
}

void add_elastic_energy(const BodyModel& body, const Eigen::VectorXd& q, double& sum) {
  for (const FemTet& tet : body.tets) {
    sum += kernels::tet_stable_neo_hookean_energy(tet_positions(q, body.dof_offset, tet),
                                                  tet.rest_shape_inverse, tet.rest_volume,
                                                  body.elasticity);
  }
}

void tet_stiffness(const BodyModel& body, const Eigen::VectorXd& q,
                   std::vector<Matrix12d>& stiffness) {
  stiffness.resize(body.tets.size());
  for (std::size_t t = 0; t < body.tets.size(); ++t) {
    const FemTet& tet = body.tets[t];
    stiffness[t] = kernels::tet_stable_neo_hookean_hessian(tet_positions(q, body.dof_offset, tet),
                                                           tet.rest_shape_inverse, tet.rest_volume,
                                                           body.elasticity, true);
  }
}

void add_damping_energy(const BodyModel& body, const Eigen::VectorXd& q,
                        const Eigen::VectorXd& q_start, const std::vector<Matrix12d>& stiffness,
                        double h, double& sum) {
  const double c = body.material.damping / h;
  for (std::size_t t = 0; t < body.tets.size(); ++t) {
    const FemTet& tet = body.tets[t];
    const Vector12 dx =
        tet_positions(q, body.dof_offset, tet) - tet_positions(q_start, body.dof_offset, tet);
    sum += 0.5 * c * dx.dot(stiffness[t] * dx);
  }
}

void add_elastic_derivatives(const BodyModel& body, const Eigen::VectorXd& q, double scale,
                             const StepDamping* damping, Eigen::VectorXd& gradient,
                             std::vector<Eigen::Triplet<double>>* hessian) {
  const Eigen::Index dofs = 3 * body.rest.rows();
  const bool at_start = damping != nullptr && q.segment(body.dof_offset, dofs) ==
                                                  damping->q_start.segment(body.dof_offset, dofs);
  const double c = damping ? body.material.damping / damping->h : 0.0;
  for (std::size_t t = 0; t < body.tets.size(); ++t) {
    const FemTet& tet = body.tets[t];
    const Vector12 x = tet_positions(q, body.dof_offset, tet);
    const Eigen::Matrix3d f = kernels::deformation_gradient(x, tet.rest_shape_inverse);
    Vector12 g = kernels::tet_stable_neo_hookean_gradient(f, tet.rest_shape_inverse,
                                                          tet.rest_volume, body.elasticity);
    if (damping) {
      g +=
          c * (damping->stiffness[t] * (x - tet_positions(damping->q_start, body.dof_offset, tet)));
    }
    add_tet_gradient(body, tet, scale * g, gradient);
    if (!hessian) continue;
    Matrix12 h = at_start ? damping->stiffness[t]
                          : kernels::tet_stable_neo_hookean_hessian(
                                f, tet.rest_shape_inverse, tet.rest_volume, body.elasticity, true);
    if (damping) h += c * damping->stiffness[t];
    add_tet_hessian(body, tet, scale * h, *hessian);
  }
}

}  // namespace grip::solver::fem
