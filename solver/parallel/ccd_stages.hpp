#pragma once
// The data-parallel engine's step bound, one source for every launcher (launch.hpp), as the CPU
// engine's collision_free_fraction computes it: per contact pair of a batch (point-triangle or
// edge-edge, in the batch's collision vertex numbering), additive CCD's time of impact on the
// straight path from the start positions to the end positions (kernels/accd.hpp), 1 where the
// pair does not meet on it; then per environment the smallest of its pairs', the fraction of
// the Newton step it may take. A minimum is exact, so the order of the pairs does not matter.
#include <Eigen/Core>

#include "solver/kernels/accd.hpp"
#include "solver/kernels/hd.hpp"

namespace grip::solver::parallel {

struct CcdStage {
  const int* vertex = nullptr;               // 4 per pair: collision vertices of the batch
  const unsigned char* edge_edge = nullptr;  // per pair: 1 edge-edge, 0 point-triangle
  const double* start = nullptr;             // 3 per collision vertex
  const double* end = nullptr;               // 3 per collision vertex
  double rescaling = 0.1;                    // ACCD's s (SimParameters::ccd_rescaling)
  double* toi = nullptr;                     // per pair

  GRIP_HD void operator()(int k) const {
    Eigen::Vector3d s[4], e[4];
    for (int c = 0; c < 4; ++c) {
      const int v = vertex[4 * k + c];
      s[c] = Eigen::Vector3d(start[3 * v], start[3 * v + 1], start[3 * v + 2]);
      e[c] = Eigen::Vector3d(end[3 * v], end[3 * v + 1], end[3 * v + 2]);
    }
    kernels::AccdOptions options;
    options.rescaling = rescaling;
    const kernels::AccdResult impact =
        edge_edge[k]
            ? kernels::edge_edge_accd(s[0], s[1], s[2], s[3], e[0], e[1], e[2], e[3], options)
            : kernels::point_triangle_accd(s[0], s[1], s[2], s[3], e[0], e[1], e[2], e[3], options);
    toi[k] = impact.impact ? impact.toi : 1.0;
  }
};

// Per environment: the smallest of its pairs' values, 1 for an environment without pairs.
struct EnvironmentMinStage {
  const int* pair_begin = nullptr;  // environment_count + 1 offsets
  const double* value = nullptr;    // per pair
  double* minimum = nullptr;        // per environment

  GRIP_HD void operator()(int e) const {
    double smallest = 1.0;
    for (int k = pair_begin[e]; k < pair_begin[e + 1]; ++k) {
      smallest = value[k] < smallest ? value[k] : smallest;
    }
    minimum[e] = smallest;
  }
};

}  // namespace grip::solver::parallel
