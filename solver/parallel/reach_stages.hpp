#pragma once
// Which of a batch's broad-phase candidates (broad_phase.hpp) matter on a path, all environments
// at once, as the CPU engine's within_reach decides (solver/contact/candidates.hpp): a pair is
// within reach when its distance at the start is at most d_hat plus the largest displacements
// of its two sides (a body's own pairs: displacements less the body's common motion), and CCD
// watches it when it is within reach or starts beyond d_hat / ccd_rescaling and additive CCD
// would not clear it at its first advance. Each candidate gets two flags; the flags are scanned
// into offsets and the candidates written, in their order, into the two lists.
#include <cmath>
#include <cstddef>

#include "solver/kernels/aabb.hpp"
#include "solver/kernels/accd.hpp"
#include "solver/kernels/edge_edge_distance.hpp"
#include "solver/kernels/hd.hpp"
#include "solver/kernels/point_triangle_distance.hpp"
#include "solver/parallel/launch.hpp"
#include "solver/parallel/surface_batch.hpp"

namespace grip::solver::parallel {

struct ReachBuffers {
  SurfaceBuffers surface;
  const double* start = nullptr;  // 3 per vertex
  const double* end = nullptr;
  const double* d_hat = nullptr;          // per environment
  const double* ccd_rescaling = nullptr;  // per environment
  // The candidates (CandidateBuffers' sorted arrays) and each environment's first.
  int count = 0;
  const int* vertex = nullptr;  // 4 per candidate
  const unsigned char* edge_edge = nullptr;
  const int* environment = nullptr;
  const int* candidate_begin = nullptr;  // environments + 1
  // Work: per vertex |end - start| and the same less its body's common motion; per body the
  // centre of the box of its vertices' displacements (3).
  double* moved = nullptr;
  double* moved_in_body = nullptr;
  double* body_shift = nullptr;
  // Per candidate (and one more) a flag, then its offset, for each list; the lists and each
  // environment's first entry in them.
  int* reachable_offset = nullptr;
  int* ccd_offset = nullptr;
  int* reachable = nullptr;  // candidate indices
  int* ccd = nullptr;
  int* reachable_begin = nullptr;  // environments + 1
  int* ccd_begin = nullptr;
};

GRIP_HD inline Eigen::Vector3d row3(const double* x, int v) {
  return Eigen::Vector3d(x[3 * v], x[3 * v + 1], x[3 * v + 2]);
}

struct DisplacementStage {
  ReachBuffers r;
  GRIP_HD void operator()(int v) const {
    r.moved[v] = Eigen::Vector3d(row3(r.end, v) - row3(r.start, v)).norm();
  }
};

// A body's common motion: the centre of the box of its vertices' displacements.
struct BodyShiftStage {
  ReachBuffers r;
  GRIP_HD void operator()(int body) const {
    const SurfaceBuffers& s = r.surface;
    Aabb shared;
    for (int v = s.body_vertex_begin[body]; v < s.body_vertex_begin[body + 1]; ++v) {
      shared.expand(Eigen::Vector3d(row3(r.end, v) - row3(r.start, v)));
    }
    const Eigen::Vector3d center = shared.center();
    for (int k = 0; k < 3; ++k) r.body_shift[3 * body + k] = center[k];
  }
};

struct DisplacementInBodyStage {
  ReachBuffers r;
  GRIP_HD void operator()(int v) const {
    const Eigen::Vector3d shift = row3(r.body_shift, r.surface.vertex_body[v]);
    r.moved_in_body[v] = Eigen::Vector3d(row3(r.end, v) - row3(r.start, v) - shift).norm();
  }
};

// The two flags of candidate k (item count: the zeros past the last, for the scans).
struct ReachStage {
  ReachBuffers r;

  // Whether additive CCD from start to end clears the pair at its first advance, d_sq its
  // squared distance at the start (the CPU engine's ccd_clears_at_once, margins included).
  GRIP_HD bool ccd_clears_at_once(const int* v, bool edge_edge, double d_sq,
                                  double rescaling) const {
    Eigen::Matrix<double, 3, 4> dx;
    for (int c = 0; c < 4; ++c) dx.col(c) = row3(r.end, v[c]) - row3(r.start, v[c]);
    const double l_p = kernels::accd_relative_motion(dx, edge_edge);
    kernels::AccdOptions options;
    options.rescaling = rescaling;
    return kernels::accd_clears_at_first_advance(std::sqrt(d_sq) * (1.0 - 1e-6), l_p * (1.0 + 1e-6),
                                                 options);
  }

  GRIP_HD void operator()(int k) const {
    if (k == r.count) {
      r.reachable_offset[k] = r.ccd_offset[k] = 0;
      return;
    }
    const int* v = r.vertex + 4 * k;
    const bool edge_edge = r.edge_edge[k] != 0;
    const int e = r.environment[k], second = edge_edge ? 2 : 1;
    const double d_hat = r.d_hat[e], rescaling = r.ccd_rescaling[e];
    const bool one_body = r.surface.vertex_body[v[0]] == r.surface.vertex_body[v[2]];
    const double* moved = one_body ? r.moved_in_body : r.moved;
    double a = 0.0, b = 0.0;  // each side's largest displacement
    for (int c = 0; c < 4; ++c) {
      double& side = c < second ? a : b;
      side = c == 0 || c == second || moved[v[c]] > side ? moved[v[c]] : side;
    }
    const double reach = d_hat + a + b;
    Aabb box_a, box_b;  // the primitives' boxes at the start: their distance bounds the pair's
    for (int c = 0; c < 4; ++c) (c < second ? box_a : box_b).expand(row3(r.start, v[c]));
    const double lower_sq = box_a.distance_sq(box_b);
    bool within = false, watched = false;
    if (!(lower_sq > reach * reach * (1.0 + 1e-5) &&
          ccd_clears_at_once(v, edge_edge, lower_sq, rescaling))) {
      const Eigen::Vector3d x0 = row3(r.start, v[0]), x1 = row3(r.start, v[1]),
                            x2 = row3(r.start, v[2]), x3 = row3(r.start, v[3]);
      const double d_sq = edge_edge ? kernels::edge_edge_distance_sq(x0, x1, x2, x3)
                                    : kernels::point_triangle_distance_sq(x0, x1, x2, x3);
      const double stops = d_hat * (1.0 - 1e-6) / rescaling;
      within = d_sq <= reach * reach * (1.0 + 1e-6);
      watched =
          within || (d_sq >= stops * stops && !ccd_clears_at_once(v, edge_edge, d_sq, rescaling));
    }
    r.reachable_offset[k] = within ? 1 : 0;
    r.ccd_offset[k] = watched ? 1 : 0;
  }
};

// Candidate k into the lists its (scanned) flags put it in.
struct ReachScatterStage {
  ReachBuffers r;
  GRIP_HD void operator()(int k) const {
    if (r.reachable_offset[k + 1] > r.reachable_offset[k]) r.reachable[r.reachable_offset[k]] = k;
    if (r.ccd_offset[k + 1] > r.ccd_offset[k]) r.ccd[r.ccd_offset[k]] = k;
  }
};

struct ReachBeginStage {
  ReachBuffers r;
  GRIP_HD void operator()(int e) const {
    r.reachable_begin[e] = r.reachable_offset[r.candidate_begin[e]];
    r.ccd_begin[e] = r.ccd_offset[r.candidate_begin[e]];
  }
};

// The reach filter's work and lists in host (HostArray) or device (DeviceArray) memory.
template <template <class> class Array>
struct ReachStorage {
  ReachStorage(const SurfaceBuffers& s, int count)
      : moved(std::size_t(s.vertex_count)),
        moved_in_body(std::size_t(s.vertex_count)),
        body_shift(3 * std::size_t(s.body_count)),
        reachable_offset(std::size_t(count) + 1),
        ccd_offset(std::size_t(count) + 1),
        reachable(std::size_t(count)),
        ccd(std::size_t(count)),
        reachable_begin(std::size_t(s.environment_count) + 1),
        ccd_begin(std::size_t(s.environment_count) + 1) {}

  // The filter's buffers over a scene's path and the candidates' sorted arrays.
  ReachBuffers buffers(const SurfaceBuffers& s, const double* start, const double* end,
                       const double* d_hat, const double* ccd_rescaling, int count,
                       const int* vertex, const unsigned char* edge_edge, const int* environment,
                       const int* environment_begin) {
    return {s,
            start,
            end,
            d_hat,
            ccd_rescaling,
            count,
            vertex,
            edge_edge,
            environment,
            environment_begin,
            moved.data(),
            moved_in_body.data(),
            body_shift.data(),
            reachable_offset.data(),
            ccd_offset.data(),
            reachable.data(),
            ccd.data(),
            reachable_begin.data(),
            ccd_begin.data()};
  }

  Array<double> moved, moved_in_body, body_shift;
  Array<int> reachable_offset, ccd_offset, reachable, ccd, reachable_begin, ccd_begin;
};

// Flags every candidate, scans the flags into offsets and writes both lists with each
// environment's first entry; returns the lists' lengths (reachable, watched by CCD).
template <class Launcher>
void find_within_reach(Launcher& launch, const ReachBuffers& r, int& reachable, int& watched) {
  const SurfaceBuffers& s = r.surface;
  launch(s.vertex_count, DisplacementStage{r});
  launch(s.body_count, BodyShiftStage{r});
  launch(s.vertex_count, DisplacementInBodyStage{r});
  launch(r.count + 1, ReachStage{r});
  launch.exclusive_scan(r.reachable_offset, r.count + 1);
  launch.exclusive_scan(r.ccd_offset, r.count + 1);
  launch(r.count, ReachScatterStage{r});
  launch(s.environment_count + 1, ReachBeginStage{r});
  reachable = launch.fetch(r.reachable_offset + r.count);
  watched = launch.fetch(r.ccd_offset + r.count);
}

}  // namespace grip::solver::parallel
