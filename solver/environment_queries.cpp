// Environment's read-only views of its state: positions, centres of mass, rotations, volumes
// and contact forces, between steps.
#include <algorithm>
#include <cmath>
#include <limits>

#include "solver/body/body.hpp"
#include "solver/contact/candidates.hpp"
#include "solver/environment.hpp"
#include "solver/kernels/edge_edge_distance.hpp"
#include "solver/kernels/point_triangle_distance.hpp"

namespace grip::solver {

Vertices Environment::collision_positions() const {
  return solver::collision_positions(*model_, state_.q, targets_at_rest(*model_, state_), 0.0);
}

Vertices Environment::body_vertices(int index) const {
  const BodyModel& body = model_->bodies()[index];
  Vertices x(body.rest.rows(), 3);
  for (Eigen::Index v = 0; v < body.rest.rows(); ++v) {
    x.row(v) = vertex_position(body, state_.q, state_.poses[index], static_cast<int>(v));
  }
  return x;
}

Eigen::Vector3d Environment::center_of_mass(int index) const {
  return solver::center_of_mass(model_->bodies()[index], index, state_);
}

Eigen::Vector3d Environment::center_of_mass_velocity(int index) const {
  return solver::center_of_mass_velocity(model_->bodies()[index], index, state_);
}

Eigen::Matrix3d Environment::rotation(int index) const {
  return body_rotation(model_->bodies()[index], index, state_);
}

double Environment::min_volume_ratio() const { return solver::min_volume_ratio(*model_, state_.q); }

VertexContactForces Environment::vertex_contact_forces() const {
  return solver::vertex_contact_forces(*model_, newton_.potential(), collision_positions());
}

double Environment::surface_distance(const std::vector<int>& bodies, int other,
                                     double search) const {
  const Vertices x = collision_positions();
  const std::vector<int>& vertex_body = model_->collision().vertex_body;
  const auto in_set = [&](int v) {
    return std::find(bodies.begin(), bodies.end(), vertex_body[v]) != bodies.end();
  };
  double nearest_sq = std::numeric_limits<double>::infinity();
  for (const ContactCandidate& c : find_contact_candidates(*model_, x, x, search)) {
    // Point-triangle: vertex 0 against 1-3; edge-edge: 0-1 against 2-3.
    const int a = c.vertex[0], b = c.vertex[c.edge_edge ? 2 : 1];
    const bool between =
        (in_set(a) && vertex_body[b] == other) || (in_set(b) && vertex_body[a] == other);
    if (!between) continue;
    const auto p = [&](int k) -> Eigen::Vector3d { return x.row(c.vertex[k]).transpose(); };
    const double d_sq = c.edge_edge ? kernels::edge_edge_distance_sq(p(0), p(1), p(2), p(3))
                                    : kernels::point_triangle_distance_sq(p(0), p(1), p(2), p(3));
    nearest_sq = std::min(nearest_sq, d_sq);
  }
  const double nearest = std::sqrt(nearest_sq);
  return nearest < search ? nearest : std::numeric_limits<double>::infinity();
}

}  // namespace grip::solver
