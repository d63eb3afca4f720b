#include "solver/body/fem_bodies.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace grip::solver {
namespace {

// A tet's four vertices' 3-vectors in `values` (positions, or DOF changes), stacked.
Vector12d tet_values(const Eigen::VectorXd& values, int offset, const std::array<int, 4>& tet) {
  Vector12d x;
  for (int i = 0; i < 4; ++i) x.segment<3>(3 * i) = values.segment<3>(offset + 3 * tet[i]);
  return x;
}

// Scatters one tet's 12-vector gradient into the DOF-space gradient, and its 12x12 Hessian
// into the lower-triangle triplets.
void add_tet_gradient(int offset, const std::array<int, 4>& tet, const Vector12d& g,
                      Eigen::VectorXd& gradient) {
  for (int a = 0; a < 4; ++a) gradient.segment<3>(offset + 3 * tet[a]) += g.segment<3>(3 * a);
}

// The 78 lower-triangle entries of a tet's Hessian (its four vertices are distinct), written
// through a pointer: with emplace_back, the vector's capacity test and the store of its end after
// every entry were the most sampled instructions of the FEM derivatives.
void add_tet_hessian(int offset, const std::array<int, 4>& tet, const Matrix12d& h,
                     Triplets& hessian) {
  constexpr std::size_t kLowerEntries = 4 * 6 + 6 * 9;
  const std::size_t first = hessian.size();
  hessian.resize(first + kLowerEntries);
  Eigen::Triplet<double>* out = hessian.data() + first;
  for (int a = 0; a < 4; ++a) {
    const int row = offset + 3 * tet[a];
    for (int b = 0; b < 4; ++b) {
      const int col = offset + 3 * tet[b];
      if (row < col) continue;
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
          if (row + i >= col + j) *out++ = {row + i, col + j, h(3 * a + i, 3 * b + j)};
        }
      }
    }
  }
}

// A tet of the body's rest shape, its volume checked.
struct RestTet {
  std::array<int, 4> vertices;
  Eigen::Matrix3d rest_shape_inverse;
  double rest_volume = 0.0;
};

RestTet rest_tet(const BodyDescription& description, const Vertices& rest, Eigen::Index t) {
  RestTet tet;
  for (int i = 0; i < 4; ++i) tet.vertices[i] = description.tets(t, i);
  const Eigen::Vector3d x0 = rest.row(tet.vertices[0]), x1 = rest.row(tet.vertices[1]),
                        x2 = rest.row(tet.vertices[2]), x3 = rest.row(tet.vertices[3]);
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

// The rest shape is the start shape, in world coordinates.
void FemBodies::build(const BodyDescription& description) {
  check(description);
  const Eigen::Matrix3d r = description.pose.rotation.normalized().toRotationMatrix();
  const Vertices rest =
      (description.vertices * r.transpose()).rowwise() + description.pose.position.transpose();
  Eigen::VectorXd vertex_mass = Eigen::VectorXd::Zero(rest.rows());
  std::vector<RestTet> tets;
  for (Eigen::Index t = 0; t < description.tets.rows(); ++t) {
    tets.push_back(rest_tet(description, rest, t));
    for (int i = 0; i < 4; ++i) {
      vertex_mass[tets.back().vertices[i]] +=
          description.material.density * tets.back().rest_volume / 4.0;
    }
  }
  if ((vertex_mass.array() <= 0).any()) {
    invalid_body(description, "has a vertex that belongs to no tetrahedron");
  }
  const double mass = vertex_mass.sum();
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  for (Eigen::Index v = 0; v < rest.rows(); ++v) {
    rest_.push_back(rest.row(v).transpose());
    vertex_mass_.push_back(vertex_mass[v]);
    center += vertex_mass[v] * rest.row(v).transpose();
  }
  for (const RestTet& tet : tets) {
    tet_vertices_.push_back(tet.vertices);
    rest_shape_inverse_.push_back(tet.rest_shape_inverse);
    rest_volume_.push_back(tet.rest_volume);
  }
  vertex_begin_.push_back(static_cast<int>(rest_.size()));
  tet_begin_.push_back(static_cast<int>(tet_vertices_.size()));
  mass_.push_back(mass);
  elasticity_.push_back(kernels::stable_neo_hookean_parameters(description.material.youngs,
                                                               description.material.poisson));
  damping_.push_back(description.material.damping);
  center_of_mass_offset_.push_back(r.transpose() * (center / mass - description.pose.position));
}

Eigen::VectorXd FemBodies::vertex_masses(int i) const {
  return Eigen::Map<const Eigen::VectorXd>(vertex_mass_.data() + vertex_begin_[i], vertex_count(i));
}

std::span<const std::array<int, 4>> FemBodies::tets(int i) const {
  return {tet_vertices_.data() + tet_begin_[i],
          static_cast<std::size_t>(tet_begin_[i + 1] - tet_begin_[i])};
}

Eigen::Vector3d FemBodies::center_of_mass_offset(int i) const {
  return center_of_mass_offset_[static_cast<std::size_t>(i)];
}

void FemBodies::couple_blocks(int i, const std::function<void(int, int)>& couple) const {
  for (const std::array<int, 4>& tet : tets(i)) {
    for (int a : tet) {
      for (int b : tet) {
        if (a != b) couple(a, b);
      }
    }
  }
}

// Start positions, and velocities from the description's linear and angular velocity about the
// centre of mass.
void FemBodies::initial_state(int i, const BodyDescription& description, State& state) const {
  const int first = vertex_begin_[i], n = vertex_count(i), o = dof_offset(i);
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  for (int v = 0; v < n; ++v) com += vertex_mass_[first + v] * rest_[first + v];
  com /= mass_[i];
  for (int v = 0; v < n; ++v) {
    const Eigen::Vector3d x = rest_[first + v];
    state.q.segment<3>(o + 3 * v) = x;
    state.v.segment<3>(o + 3 * v) =
        description.velocity + description.angular_velocity.cross(x - com);
  }
}

void FemBodies::place(int i, const Eigen::Isometry3d& motion, State& state) const {
  const Eigen::Matrix3d r = motion.linear();
  const Eigen::Vector3d t = motion.translation();
  for (int v = 0; v < vertex_count(i); ++v) {
    const int o = dof_offset(i) + 3 * v;
    state.q.segment<3>(o) = r * state.q.segment<3>(o) + t;
    state.v.segment<3>(o) = r * state.v.segment<3>(o);
  }
}

// The four vertices of the tet whose centroid is nearest the centre of mass: held there, the
// body still deforms around them.
std::vector<int> FemBodies::held_dofs(int i, const State& state) const {
  const Eigen::Vector3d center = center_of_mass(i, state);
  const int o = dof_offset(i);
  const auto vertex = [&](int v) { return state.q.segment<3>(o + 3 * v); };
  const std::array<int, 4>* nearest = nullptr;
  double nearest_sq = std::numeric_limits<double>::infinity();
  for (const std::array<int, 4>& tet : tets(i)) {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (int v : tet) centroid += 0.25 * vertex(v);
    if ((centroid - center).squaredNorm() < nearest_sq) {
      nearest_sq = (centroid - center).squaredNorm();
      nearest = &tet;
    }
  }
  std::vector<int> dofs;
  for (int v : *nearest) {
    for (int k = 0; k < 3; ++k) dofs.push_back(o + 3 * v + k);
  }
  return dofs;
}

Eigen::Vector3d FemBodies::mass_weighted_mean(int i, const Eigen::VectorXd& values) const {
  const int first = vertex_begin_[i], o = dof_offset(i);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int v = 0; v < vertex_count(i); ++v) {
    sum += vertex_mass_[first + v] * values.segment<3>(o + 3 * v);
  }
  return sum / mass_[i];
}

Eigen::Vector3d FemBodies::center_of_mass(int i, const State& state) const {
  return mass_weighted_mean(i, state.q);
}

Eigen::Vector3d FemBodies::center_of_mass_velocity(int i, const State& state) const {
  return mass_weighted_mean(i, state.v);
}

// The rotation of the best rigid fit of the vertices to the rest shape.
Eigen::Matrix3d FemBodies::rotation(int i, const State& state) const {
  const int first = vertex_begin_[i], n = vertex_count(i), o = dof_offset(i);
  Eigen::Vector3d rest_com = Eigen::Vector3d::Zero();
  for (int v = 0; v < n; ++v) rest_com += vertex_mass_[first + v] * rest_[first + v];
  rest_com /= mass_[i];
  const Eigen::Vector3d com = mass_weighted_mean(i, state.q);
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (int v = 0; v < n; ++v) {
    covariance += vertex_mass_[first + v] * (state.q.segment<3>(o + 3 * v) - com) *
                  (rest_[first + v] - rest_com).transpose();
  }
  return nearest_rotation(covariance);
}

void FemBodies::vertex_positions(int i, const Eigen::VectorXd& q, const Pose& /*pose*/,
                                 std::span<const int> vertices, Vertices& out,
                                 Eigen::Index first_row) const {
  const int o = dof_offset(i);
  for (std::size_t k = 0; k < vertices.size(); ++k) {
    out.row(first_row + static_cast<Eigen::Index>(k)) = q.segment<3>(o + 3 * vertices[k]);
  }
}

VertexJacobian FemBodies::vertex_jacobian(int /*i*/, int /*v*/) const {
  return Eigen::Matrix3d::Identity();
}

double FemBodies::max_displacement(int i, const Eigen::VectorXd& dq) const {
  double largest = 0.0;
  for (int v = 0; v < vertex_count(i); ++v) {
    largest = std::max(largest, dq.segment<3>(dof_offset(i) + 3 * v).norm());
  }
  return largest;
}

double FemBodies::min_volume_ratio(int i, const Eigen::VectorXd& q) const {
  const TetView tets = tet_view(i);
  double ratio = 1.0;
  for (int k = 0; k < tets.count; ++k) {
    const Vector12d x = tet_values(q, dof_offset(i), tets.vertices[k]);
    ratio =
        std::min(ratio, kernels::deformation_gradient(x, tets.rest_shape_inverse[k]).determinant());
  }
  return ratio;
}

// h^2 g added to the inertia target of every vertex.
void FemBodies::add_gravity(int i, const Eigen::Vector3d& gravity, double h,
                            Eigen::VectorXd& q_tilde) const {
  for (int v = 0; v < vertex_count(i); ++v) {
    q_tilde.segment<3>(dof_offset(i) + 3 * v) += h * h * gravity;
  }
}

void FemBodies::add_inertia_energy(int i, const Eigen::VectorXd& q, const Eigen::VectorXd& q_tilde,
                                   double& sum) const {
  const int first = vertex_begin_[i], o = dof_offset(i);
  for (int v = 0; v < vertex_count(i); ++v) {
    const auto dx = q.segment<3>(o + 3 * v) - q_tilde.segment<3>(o + 3 * v);
    sum += 0.5 * vertex_mass_[first + v] * dx.squaredNorm();
  }
}

// The Hessian is diagonal.
void FemBodies::add_inertia_derivatives(int i, const Eigen::VectorXd& q,
                                        const Eigen::VectorXd& q_tilde, double scale,
                                        Eigen::VectorXd& gradient, Triplets* hessian) const {
  const int first = vertex_begin_[i];
  for (int v = 0; v < vertex_count(i); ++v) {
    const int o = dof_offset(i) + 3 * v;
    const double mass = scale * vertex_mass_[first + v];
    gradient.segment<3>(o) += mass * (q.segment<3>(o) - q_tilde.segment<3>(o));
    if (!hessian) continue;
    for (int k = 0; k < 3; ++k) hessian->emplace_back(o + k, o + k, mass);
  }
}

void FemBodies::add_elastic_energy(int i, const Eigen::VectorXd& q, double& sum) const {
  const TetView tets = tet_view(i);
  for (int k = 0; k < tets.count; ++k) {
    sum += kernels::tet_stable_neo_hookean_energy(tet_values(q, dof_offset(i), tets.vertices[k]),
                                                  tets.rest_shape_inverse[k], tets.rest_volume[k],
                                                  tets.elasticity);
  }
}

void FemBodies::damping_stiffness(int i, const Eigen::VectorXd& q,
                                  std::vector<Matrix12d>& stiffness) const {
  const TetView tets = tet_view(i);
  stiffness.resize(static_cast<std::size_t>(tets.count));
  for (int k = 0; k < tets.count; ++k) {
    stiffness[k] = kernels::tet_stable_neo_hookean_hessian(
        tet_values(q, dof_offset(i), tets.vertices[k]), tets.rest_shape_inverse[k],
        tets.rest_volume[k], tets.elasticity, true);
  }
}

void FemBodies::add_damping_energy(int i, const Eigen::VectorXd& q, const StepDamping& damping,
                                   double& sum) const {
  const TetView tets = tet_view(i);
  const double c = damping_[i] / damping.h;
  for (int k = 0; k < tets.count; ++k) {
    const Vector12d dx = tet_values(q, dof_offset(i), tets.vertices[k]) -
                         tet_values(damping.q_start, dof_offset(i), tets.vertices[k]);
    sum += 0.5 * c * dx.dot(damping.stiffness[k] * dx);
  }
}

void FemBodies::add_elastic_derivatives(int i, const Eigen::VectorXd& q, double scale,
                                        const StepDamping* damping, Eigen::VectorXd& gradient,
                                        Triplets* hessian) const {
  const TetView tets = tet_view(i);
  const int o = dof_offset(i);
  const Eigen::Index dofs = dof_count(i);
  const bool at_start =
      damping != nullptr && q.segment(o, dofs) == damping->q_start.segment(o, dofs);
  const double c = damping ? damping_[i] / damping->h : 0.0;
  for (int k = 0; k < tets.count; ++k) {
    const std::array<int, 4>& tet = tets.vertices[k];
    const Eigen::Matrix3d& dm_inverse = tets.rest_shape_inverse[k];
    const Vector12d x = tet_values(q, o, tet);
    const Eigen::Matrix3d f = kernels::deformation_gradient(x, dm_inverse);
    Vector12d g = kernels::tet_stable_neo_hookean_gradient(f, dm_inverse, tets.rest_volume[k],
                                                           tets.elasticity);
    if (damping) g += c * (damping->stiffness[k] * (x - tet_values(damping->q_start, o, tet)));
    add_tet_gradient(o, tet, scale * g, gradient);
    if (!hessian) continue;
    Matrix12d h = at_start ? damping->stiffness[k]
                           : kernels::tet_stable_neo_hookean_hessian(
                                 f, dm_inverse, tets.rest_volume[k], tets.elasticity, true);
    if (damping) h += c * damping->stiffness[k];
    add_tet_hessian(o, tet, scale * h, *hessian);
  }
}

FemBodies::TetView FemBodies::tet_view(int i) const {
  const int first = tet_begin_[i];
  return {tet_begin_[i + 1] - first, tet_vertices_.data() + first,
          rest_shape_inverse_.data() + first, rest_volume_.data() + first, elasticity_[i]};
}

}  // namespace grip::solver
