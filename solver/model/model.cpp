#include "solver/model/model.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "solver/contact/candidates.hpp"
#include "solver/linear/block_ordering.hpp"
#include "solver/linear/sparse_cholesky.hpp"

namespace grip::solver {
namespace {

void check_surface(const BodyDescription& body) {
  if (body.vertices.rows() == 0 || body.triangles.rows() == 0) invalid_body(body, "has no surface");
  if (!body.vertices.allFinite()) invalid_body(body, "has non-finite vertex coordinates");
  if (body.triangles.minCoeff() < 0 || body.triangles.maxCoeff() >= body.vertices.rows()) {
    invalid_body(body, "has a triangle index outside its vertices");
  }
}

// Blocks of the Newton matrix: as each kind reports them (3 DOFs per FEM vertex, 12 per affine
// body), coupled by the elements it reports (tets); a pinned vertex is solved for by an
// identity row, so it couples to nothing.
BlockGraph block_graph(const Model& model) {
  BlockGraph graph;
  std::vector<int> first_block;  // per body
  for (const BodyModel& body : model.bodies()) {
    first_block.push_back(static_cast<int>(graph.block_offset.size()));
    const int size = body.kind->block_size();
    for (int d = 0; d < body.dof_count; d += size)
      graph.block_offset.push_back(body.dof_offset + d);
  }
  graph.block_offset.push_back(model.dof_count());
  graph.neighbours.resize(graph.block_offset.size() - 1);
  const std::vector<char>& prescribed = model.prescribed();
  for (std::size_t b = 0; b < model.bodies().size(); ++b) {
    const BodyModel& body = model.bodies()[b];
    const int size = body.kind->block_size();
    auto free = [&](int block) { return !prescribed[body.dof_offset + size * block]; };
    body.kind->couple_blocks(body.local, [&](int i, int j) {
      if (free(i) && free(j)) graph.neighbours[first_block[b] + i].push_back(first_block[b] + j);
    });
  }
  return graph;
}

}  // namespace

std::shared_ptr<const Model> Model::build(const SceneDescription& scene) {
  auto model = std::make_shared<Model>();
  model->scene_ = scene;
  model->sim_ = scene.sim;
  model->build_bodies();
  model->build_collision_mesh();
  model->build_pair_friction();
  model->build_untouching();
  model->build_pins();
  model->ordering_ =
      std::make_shared<const std::vector<int>>(nested_dissection_ordering(block_graph(*model)));
  model->build_rest_proximity();
  return model;
}

std::size_t Model::contact_free_factor_bytes() const {
  // The lower triangle of the Newton matrix's pattern, column by column: a free DOF couples to
  // the free DOFs of its own block and of the blocks it shares a tet with; a prescribed one is
  // an identity row.
  const BlockGraph graph = block_graph(*this);
  std::vector<int> outer{0};
  std::vector<int> inner;
  for (std::size_t b = 0; b < graph.neighbours.size(); ++b) {
    std::vector<int> coupled = graph.neighbours[b];
    coupled.push_back(static_cast<int>(b));
    std::sort(coupled.begin(), coupled.end());
    coupled.erase(std::unique(coupled.begin(), coupled.end()), coupled.end());
    for (int col = graph.block_offset[b]; col < graph.block_offset[b + 1]; ++col) {
      if (prescribed_[col]) {
        inner.push_back(col);
      } else {
        for (const int c : coupled) {
          for (int row = std::max(col, graph.block_offset[c]); row < graph.block_offset[c + 1];
               ++row) {
            if (!prescribed_[row]) inner.push_back(row);
          }
        }
      }
      outer.push_back(static_cast<int>(inner.size()));
    }
  }
  return symbolic_factor_bytes(dof_count_, outer, inner, *ordering_);
}

double Model::min_volume_ratio(const Eigen::VectorXd& q) const {
  double ratio = 1.0;
  for (const BodyModel& body : bodies_) {
    ratio = std::min(ratio, body.kind->min_volume_ratio(body.local, q));
  }
  return ratio;
}

// Each body into its kind, and the DOF layout: each body's DOFs after those of the bodies before
// it, as many as its kind reports.
void Model::build_bodies() {
  int dofs = 0;
  for (int index = 0; index < static_cast<int>(scene_.bodies.size()); ++index) {
    const BodyDescription& body = scene_.bodies[index];
    check_surface(body);
    const BodyRegistry::Entry entry = kinds_.add(body, index);
    entry.kind->set_dof_offset(entry.local, dofs);
    const int count = entry.kind->dof_count(entry.local);
    bodies_.push_back({body.name, body.material, dofs, count, entry.kind, entry.local});
    dofs += count;
  }
  dof_count_ = dofs;
}

// Which pairs may touch, and with what friction.
void Model::build_pair_friction() {
  const int body_count = static_cast<int>(scene_.bodies.size());
  std::vector<double>& friction = collision_.friction;
  friction.assign(static_cast<std::size_t>(body_count) * body_count, -1.0);
  for (int a = 0; a < body_count; ++a) {
    for (int b = 0; b < body_count; ++b) {
      if (!bodies_[a].has_dofs() && !bodies_[b].has_dofs()) continue;
      if (a == b && !bodies_[a].deforms()) continue;  // only a deforming body touches itself
      const int group = scene_.bodies[a].collision_group;
      if (a != b && group >= 0 && group == scene_.bodies[b].collision_group) continue;
      friction[a * body_count + b] =
          std::sqrt(scene_.bodies[a].material.friction * scene_.bodies[b].material.friction);
    }
  }
  for (const ContactOverride& c : scene_.contacts) {
    if (c.body_a < 0 || c.body_a >= body_count || c.body_b < 0 || c.body_b >= body_count) {
      throw std::invalid_argument("contact override names a body that does not exist");
    }
    if (c.friction < 0) throw std::invalid_argument("contact friction must be >= 0");
    for (const auto& [a, b] : {std::pair{c.body_a, c.body_b}, std::pair{c.body_b, c.body_a}}) {
      if (friction[a * body_count + b] >= 0) friction[a * body_count + b] = c.friction;
    }
  }
}

void Model::build_untouching() {
  const std::size_t body_count = bodies_.size();
  std::vector<char>& untouching = collision_.untouching;
  untouching.assign(body_count, 0);
  for (std::size_t b = 0; b < body_count; ++b) {
    untouching[b] = !bodies_[b].has_dofs() || scene_.bodies[b].collision_group >= 0;
  }
  for (std::size_t a = 0; a < body_count; ++a) {
    for (std::size_t b = 0; b < body_count; ++b) {
      if (untouching[a] && untouching[b] && may_touch(static_cast<int>(a), static_cast<int>(b))) {
        for (std::size_t c = 0; c < body_count; ++c) untouching[c] = !bodies_[c].has_dofs();
        return;
      }
    }
  }
}

// Pins: prescribed DOFs, and no contact between a pinned body and its mount.
void Model::build_pins() {
  const int body_count = static_cast<int>(scene_.bodies.size());
  prescribed_.assign(dof_count_, 0);
  for (int index = 0; index < body_count; ++index) {
    const BodyDescription& body = scene_.bodies[index];
    const BodyModel& b = bodies_[index];
    if (!body.pins.empty() && !b.deforms()) invalid_body(body, "only FEM bodies have pins");
    for (const Pin& pin : body.pins) {
      if (pin.kinematic_body < 0 || pin.kinematic_body >= body_count ||
          bodies_[pin.kinematic_body].has_dofs()) {
        invalid_body(body, "is pinned to something that is not a kinematic body");
      }
      const BodyDescription& mount = scene_.bodies[pin.kinematic_body];
      const Eigen::Matrix3d mount_r = mount.pose.rotation.normalized().toRotationMatrix();
      for (int v : pin.vertices) {
        if (v < 0 || v >= body.vertices.rows())
          invalid_body(body, "pins a vertex it does not have");
        // A deforming body's rest vertices are its world positions at the start.
        const Eigen::Vector3d world = b.kind->rest_vertex(b.local, v);
        pins_.push_back(
            {index, v, pin.kinematic_body, mount_r.transpose() * (world - mount.pose.position)});
        for (int k = 0; k < 3; ++k) prescribed_[b.kind->vertex_block(b.local, v) + k] = 1;
      }
      collision_.friction[index * body_count + pin.kinematic_body] = -1.0;
      collision_.friction[pin.kinematic_body * body_count + index] = -1.0;
    }
  }
}

// The collision mesh: every surface vertex, edge and face of every body, body after body.
void Model::build_collision_mesh() {
  CollisionMesh& mesh = collision_;
  for (int index = 0; index < static_cast<int>(scene_.bodies.size()); ++index) {
    const BodyDescription& body = scene_.bodies[index];
    std::map<int, int> to_collision;
    auto collision_vertex = [&](int local) {
      auto [it, added] = to_collision.try_emplace(local, mesh.size());
      if (added) {
        mesh.vertex_body.push_back(index);
        mesh.vertex_local.push_back(local);
      }
      return it->second;
    };
    std::map<std::pair<int, int>, int> edge_seen;
    for (Eigen::Index t = 0; t < body.triangles.rows(); ++t) {
      std::array<int, 3> face;
      for (int i = 0; i < 3; ++i) face[i] = collision_vertex(body.triangles(t, i));
      mesh.faces.push_back(face);
      for (int i = 0; i < 3; ++i) {
        const int a = std::min(face[i], face[(i + 1) % 3]),
                  b = std::max(face[i], face[(i + 1) % 3]);
        if (edge_seen.emplace(std::pair{a, b}, 0).second) mesh.edges.push_back({a, b});
      }
    }
    mesh.body_first_vertex.push_back(mesh.size());
  }
  mesh.rest.resize(mesh.size(), 3);
  for (int v = 0; v < mesh.size(); ++v) {
    const BodyModel& body = bodies_[mesh.vertex_body[v]];
    mesh.rest.row(v) = body.kind->rest_vertex(body.local, mesh.vertex_local[v]).transpose();
  }
}

void Model::build_rest_proximity() {
  const bool any_self_contact =
      std::any_of(bodies_.begin(), bodies_.end(), [](const BodyModel& b) { return b.deforms(); });
  if (!any_self_contact) return;
  auto [point_triangle, edge_edge] = self_pairs_near_at_rest(collision_, sim_.d_hat);
  collision_.point_triangle_near_at_rest = std::move(point_triangle);
  collision_.edge_edge_near_at_rest = std::move(edge_edge);
}

}  // namespace grip::solver
