#include "solver/parallel/broad_phase.hpp"

#include <stdexcept>

namespace grip::solver::parallel {

HostBroadPhase::HostBroadPhase(const SurfaceBatch& surfaces) : surfaces_(surfaces) {
  const SurfaceBuffers s = surfaces.buffers();
  vertex_box_.resize(6 * static_cast<std::size_t>(s.vertex_count));
  edge_box_.resize(6 * static_cast<std::size_t>(s.edge_count));
  face_box_.resize(6 * static_cast<std::size_t>(s.face_count));
  axis_.resize(static_cast<std::size_t>(s.environment_count));
  point_face_order_.resize(static_cast<std::size_t>(s.vertex_count + s.face_count));
  edge_order_.resize(static_cast<std::size_t>(s.edge_count));
  point_face_found_.resize(point_face_order_.size() + 1);
  edge_found_.resize(edge_order_.size() + 1);
  body_point_begin_.resize(static_cast<std::size_t>(s.body_count) + 1);
  body_face_begin_.resize(body_point_begin_.size());
  body_edge_begin_.resize(body_point_begin_.size());
  environment_begin_.resize(static_cast<std::size_t>(s.environment_count) + 1);
}

BroadPhaseBuffers HostBroadPhase::buffers(const std::vector<double>& start,
                                          const std::vector<double>& end,
                                          const std::vector<double>& d_hat) {
  BroadPhaseBuffers b;
  b.surface = surfaces_.buffers();
  if (start.size() != 3 * static_cast<std::size_t>(b.surface.vertex_count) ||
      end.size() != start.size() ||
      d_hat.size() != static_cast<std::size_t>(b.surface.environment_count)) {
    throw std::invalid_argument("HostBroadPhase::find: arrays do not match the batch");
  }
  b.start = start.data();
  b.end = end.data();
  b.d_hat = d_hat.data();
  b.vertex_box = vertex_box_.data();
  b.edge_box = edge_box_.data();
  b.face_box = face_box_.data();
  b.axis = axis_.data();
  b.point_face_order = point_face_order_.data();
  b.edge_order = edge_order_.data();
  b.point_face_found = point_face_found_.data();
  b.edge_found = edge_found_.data();
  b.body_point_begin = body_point_begin_.data();
  b.body_face_begin = body_face_begin_.data();
  b.body_edge_begin = body_edge_begin_.data();
  return b;
}

CandidateBuffers HostBroadPhase::candidates(const CandidateCounts& counts) {
  const auto n = static_cast<std::size_t>(counts.total());
  primitive_.resize(2 * n);
  order_.resize(n);
  vertex_.resize(4 * n);
  edge_edge_.resize(n);
  near_at_rest_.resize(n);
  friction_.resize(n);
  mollifier_eps_.resize(n);
  environment_.resize(n);
  return {primitive_.data(),     order_.data(),        vertex_.data(),
          edge_edge_.data(),     near_at_rest_.data(), friction_.data(),
          mollifier_eps_.data(), environment_.data(),  environment_begin_.data()};
}

}  // namespace grip::solver::parallel
