#include "src/trial/object_body.hpp"

#include "solver/kernels/affine_body.hpp"
#include "src/geometry/boundary_surface.hpp"
#include "src/metrics/von_mises.hpp"
#include "src/scene/primitives.hpp"

namespace grip::trial {

ObjectBody::ObjectBody(const TrialObject& object) : soft_(object.soft()), object_(object) {
  if (soft_) {
    rest_tets_ = *object.tets;
    soft_surface_ = geometry::boundary_surface(rest_tets_, &soft_surface_to_body_);
  } else {
    rigid_distance_ = std::make_unique<geometry::SignedDistance>(object.surface);
  }
}

ObjectBody::~ObjectBody() = default;
ObjectBody::ObjectBody(ObjectBody&&) noexcept = default;
ObjectBody& ObjectBody::operator=(ObjectBody&&) noexcept = default;

solver::BodyDescription ObjectBody::description(double soft_damping) const {
  solver::BodyDescription body;
  body.name = object_.name.empty() ? "object" : object_.name;
  body.material = object_.material;
  if (soft_) {
    body.type = solver::BodyType::kFem;
    body.material.damping = soft_damping;
    scene::set_fem_mesh(body, rest_tets_);
  } else {
    body.type = solver::BodyType::kAffine;
    body.vertices = object_.surface.vertices;
    body.triangles = object_.surface.triangles;
  }
  return body;
}

void ObjectBody::bind(std::shared_ptr<const solver::Model> model) {
  model_ = std::move(model);
  if (soft_) {
    const solver::BodyModel& body = model_->bodies()[0];
    const Eigen::VectorXd vertex_mass = body.kind->vertex_masses(body.local);
    const solver::Vertices rest = body.kind->rest_vertices(body.local);
    rest_center_ = (vertex_mass.transpose() * rest).transpose() / vertex_mass.sum();
  }
}

std::array<double, 12> ObjectBody::pose(const solver::EnvironmentHandle& environment) const {
  Eigen::Matrix3d a;
  Eigen::Vector3d t;
  if (soft_) {
    a = environment.rotation(0);
    t = environment.center_of_mass(0) - a * rest_center_;
  } else {
    const solver::BodyModel& body = model_->bodies()[0];
    const solver::Vector12d q = environment.dofs().segment<12>(body.dof_offset);
    a = solver::kernels::affine_body_matrix(q);
    t = q.head<3>() - a * body.kind->center_of_mass_offset(body.local);
  }
  std::array<double, 12> pose;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) pose[4 * r + c] = a(r, c);
    pose[4 * r + 3] = t[r];
  }
  return pose;
}

metrics::DistanceMetrics ObjectBody::distances(const solver::EnvironmentHandle& environment,
                                               const geometry::Vertices& points) const {
  if (soft_) {
    // The deformed object: its signed distance is built on its current surface.
    const geometry::Vertices body = environment.body_vertices(0);
    geometry::SurfaceMesh surface = soft_surface_;
    for (Eigen::Index v = 0; v < surface.vertices.rows(); ++v) {
      surface.vertices.row(v) = body.row(soft_surface_to_body_[v]);
    }
    return metrics::distance_metrics(geometry::SignedDistance(surface), points);
  }
  // A rigid object: the points are taken into the object frame (x = A x_object + t).
  const std::array<double, 12> p = pose(environment);
  Eigen::Matrix3d a;
  Eigen::Vector3d t;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) a(r, c) = p[4 * r + c];
    t[r] = p[4 * r + 3];
  }
  const Eigen::Matrix3d a_inverse = a.inverse();
  geometry::Vertices local(points.rows(), 3);
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    local.row(i) = (a_inverse * (points.row(i).transpose() - t)).transpose();
  }
  return metrics::distance_metrics(*rigid_distance_, local);
}

Eigen::VectorXd ObjectBody::stress(const solver::EnvironmentHandle& environment) const {
  if (!soft_) return {};
  const solver::Material& material = model_->bodies()[0].material;
  return metrics::von_mises_stress(rest_tets_, environment.body_vertices(0), material.youngs,
                                   material.poisson);
}

}  // namespace grip::trial
