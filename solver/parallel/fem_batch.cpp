#include "solver/parallel/fem_batch.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <stdexcept>
#include <string>

#include "solver/kernels/neo_hookean.hpp"

namespace grip::solver::parallel {

void FemBatch::begin_environment(int dof_count) {
  dof_begin_.push_back(dof_begin_.back() + dof_count);
  tet_begin_.push_back(tet_begin_.back());
  vertex_begin_.push_back(vertex_begin_.back());
}

void FemBatch::add_body(int first_dof, const std::vector<double>& rest,
                        const std::vector<int>& tets, const FemMaterial& material) {
  if (environment_count() == 0) {
    throw std::logic_error("FemBatch::add_body before begin_environment");
  }
  const int environment = environment_count() - 1;
  const int base = dof_begin_[static_cast<std::size_t>(environment)] + first_dof;
  const kernels::StableNeoHookeanParameters elasticity =
      kernels::stable_neo_hookean_parameters(material.youngs, material.poisson);
  std::vector<double> mass(rest.size() / 3, 0.0);
  const auto vertex = [&](int v) {
    return Eigen::Vector3d(rest[3 * v], rest[3 * v + 1], rest[3 * v + 2]);
  };
  for (std::size_t t = 0; 4 * t < tets.size(); ++t) {
    const int* tet = &tets[4 * t];
    const Eigen::Vector3d x0 = vertex(tet[0]), x1 = vertex(tet[1]), x2 = vertex(tet[2]),
                          x3 = vertex(tet[3]);
    const double volume = kernels::tet_rest_volume(x0, x1, x2, x3);
    if (!(volume > 0.0)) {
      throw std::invalid_argument("FemBatch: tet " + std::to_string(t) +
                                  " is flat or inverted at rest");
    }
    const Eigen::Matrix3d dm_inverse = kernels::tet_rest_shape_inverse(x0, x1, x2, x3);
    for (int c = 0; c < 4; ++c) tet_dofs_.push_back(base + 3 * tet[c]);
    tet_environment_.push_back(environment);
    rest_shape_inverse_.insert(rest_shape_inverse_.end(), dm_inverse.data(), dm_inverse.data() + 9);
    rest_volume_.push_back(volume);
    for (int c = 0; c < 4; ++c)
      mass[static_cast<std::size_t>(tet[c])] += material.density * volume / 4.0;
    mu_.push_back(elasticity.mu);
    lambda_.push_back(elasticity.lambda);
    damping_.push_back(material.damping);
  }
  tet_begin_.back() = static_cast<int>(rest_volume_.size());
  // Vertices in DOF order, as finish() lists them: environments and bodies come in DOF order.
  for (std::size_t v = 0; v < mass.size(); ++v) {
    if (!(mass[v] > 0.0)) {
      throw std::invalid_argument("FemBatch: vertex " + std::to_string(v) + " is in no tet");
    }
    vertex_dof_.push_back(base + 3 * static_cast<int>(v));
    vertex_environment_.push_back(environment);
    vertex_mass_.push_back(mass[v]);
  }
  vertex_begin_.back() = static_cast<int>(vertex_dof_.size());
}

void FemBatch::finish() {
  if (!std::is_sorted(vertex_dof_.begin(), vertex_dof_.end())) {
    throw std::logic_error("FemBatch: bodies must be added in DOF order");
  }
  // Each vertex's slots, in slot order; vertices are named by their first DOF, in DOF order.
  std::vector<std::pair<int, int>> by_vertex;  // (first DOF, slot)
  by_vertex.reserve(tet_dofs_.size());
  for (std::size_t s = 0; s < tet_dofs_.size(); ++s) {
    by_vertex.emplace_back(tet_dofs_[s], static_cast<int>(s));
  }
  std::sort(by_vertex.begin(), by_vertex.end());
  incidence_begin_.assign(1, 0);
  incidence_slots_.clear();
  std::size_t next = 0;
  for (const int dof : vertex_dof_) {
    for (; next < by_vertex.size() && by_vertex[next].first == dof; ++next) {
      incidence_slots_.push_back(by_vertex[next].second);
    }
    incidence_begin_.push_back(static_cast<int>(incidence_slots_.size()));
  }
}

TetBuffers FemBatch::tets() const {
  return {static_cast<int>(rest_volume_.size()),
          tet_dofs_.data(),
          tet_environment_.data(),
          rest_shape_inverse_.data(),
          rest_volume_.data(),
          mu_.data(),
          lambda_.data(),
          damping_.data()};
}

VertexBuffers FemBatch::vertices() const {
  return {static_cast<int>(vertex_dof_.size()), vertex_dof_.data(), vertex_environment_.data(),
          vertex_mass_.data()};
}

IncidenceBuffers FemBatch::incidence() const {
  return {static_cast<int>(vertex_dof_.size()), vertex_dof_.data(), incidence_begin_.data(),
          incidence_slots_.data()};
}

}  // namespace grip::solver::parallel
