#include "solver/parallel/surface_batch.hpp"

#include <stdexcept>

namespace grip::solver::parallel {

void SurfaceBatch::begin_environment(const std::vector<double>& friction,
                                     const std::vector<char>& untouching) {
  const auto bodies = untouching.size();
  if (friction.size() != bodies * bodies) {
    throw std::invalid_argument("SurfaceBatch: the friction table is not bodies x bodies");
  }
  const int environment = environment_count();
  body_begin_.push_back(body_begin_.back() + static_cast<int>(bodies));
  friction_.insert(friction_.end(), friction.begin(), friction.end());
  friction_begin_.push_back(static_cast<int>(friction_.size()));
  body_environment_.insert(body_environment_.end(), bodies, environment);
  body_vertex_begin_.insert(body_vertex_begin_.end(), bodies, body_vertex_begin_.back());
  untouching_.insert(untouching_.end(), untouching.begin(), untouching.end());
  vertex_begin_.push_back(vertex_begin_.back());
  point_triangle_rest_begin_.push_back(point_triangle_rest_begin_.back());
  edge_edge_rest_begin_.push_back(edge_edge_rest_begin_.back());
}

int SurfaceBatch::current() const {
  if (environment_count() == 0) {
    throw std::logic_error("SurfaceBatch: a primitive before begin_environment");
  }
  return environment_count() - 1;
}

int SurfaceBatch::vertex(int local) const {
  const int e = current();
  const int v = vertex_begin_[e] + local;
  if (local < 0 || v >= vertex_begin_[e + 1]) {
    throw std::invalid_argument("SurfaceBatch: a vertex outside its environment");
  }
  return v;
}

void SurfaceBatch::add_vertex(int body, double x, double y, double z) {
  const int e = current();
  const int global = body_begin_[e] + body;
  if (body < 0 || global >= body_begin_[e + 1]) {
    throw std::invalid_argument("SurfaceBatch: a vertex of a body outside its environment");
  }
  if (vertex_begin_[e + 1] > vertex_begin_[e] && vertex_body_.back() > global) {
    throw std::invalid_argument("SurfaceBatch: a body's vertex after a later body's");
  }
  // Every later body of the environment now starts one vertex later.
  for (int b = global + 1; b <= body_begin_[e + 1]; ++b) ++body_vertex_begin_[b];
  vertex_body_.push_back(global);
  vertex_environment_.push_back(e);
  rest_.insert(rest_.end(), {x, y, z});
  ++vertex_begin_.back();
}

void SurfaceBatch::add_edge(int a, int b) {
  edge_.insert(edge_.end(), {vertex(a), vertex(b)});
  edge_environment_.push_back(current());
}

void SurfaceBatch::add_face(int a, int b, int c) {
  face_.insert(face_.end(), {vertex(a), vertex(b), vertex(c)});
  face_environment_.push_back(current());
}

void SurfaceBatch::set_near_at_rest(const std::vector<std::array<int, 4>>& point_triangle,
                                    const std::vector<std::array<int, 4>>& edge_edge) {
  current();
  if (point_triangle_rest_begin_.back() != point_triangle_rest_begin_.end()[-2] ||
      edge_edge_rest_begin_.back() != edge_edge_rest_begin_.end()[-2]) {
    throw std::logic_error("SurfaceBatch: near-at-rest pairs set twice for one environment");
  }
  for (const auto& pair : point_triangle) {
    point_triangle_rest_.insert(point_triangle_rest_.end(), pair.begin(), pair.end());
  }
  for (const auto& pair : edge_edge) {
    edge_edge_rest_.insert(edge_edge_rest_.end(), pair.begin(), pair.end());
  }
  point_triangle_rest_begin_.back() = static_cast<int>(point_triangle_rest_.size() / 4);
  edge_edge_rest_begin_.back() = static_cast<int>(edge_edge_rest_.size() / 4);
}

SurfaceBuffers SurfaceBatch::buffers() const {
  SurfaceBuffers s;
  s.environment_count = environment_count();
  s.vertex_count = static_cast<int>(vertex_body_.size());
  s.edge_count = static_cast<int>(edge_environment_.size());
  s.face_count = static_cast<int>(face_environment_.size());
  s.body_count = static_cast<int>(body_environment_.size());
  s.body_begin = body_begin_.data();
  s.body_vertex_begin = body_vertex_begin_.data();
  s.friction_begin = friction_begin_.data();
  s.friction = friction_.data();
  s.body_environment = body_environment_.data();
  s.untouching = untouching_.data();
  s.vertex_body = vertex_body_.data();
  s.vertex_environment = vertex_environment_.data();
  s.vertex_begin = vertex_begin_.data();
  s.rest = rest_.data();
  s.edge = edge_.data();
  s.edge_environment = edge_environment_.data();
  s.face = face_.data();
  s.face_environment = face_environment_.data();
  s.point_triangle_rest_begin = point_triangle_rest_begin_.data();
  s.point_triangle_rest = point_triangle_rest_.data();
  s.edge_edge_rest_begin = edge_edge_rest_begin_.data();
  s.edge_edge_rest = edge_edge_rest_.data();
  return s;
}

}  // namespace grip::solver::parallel
