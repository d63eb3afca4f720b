#pragma once
// Additive continuous collision detection (ACCD, Li et al. 2021 "Codimensional Incremental
// Potential Contact", Algorithm 1) for point-triangle and edge-edge pairs moving linearly from
// time 0 to time 1. It returns a conservative time of impact: the pair stays apart (farther than
// the minimum separation) on [0, toi], so a step scaled by toi never overshoots.
//
// Each iteration advances t by the lower bound t_l = (1 - s) (d^2 - xi^2) / ((d + xi) l_p) of the
// time the pair needs to close its current gap d - xi, where l_p bounds the relative speed of
// any two points of the pair (after subtracting the mean displacement, which moves nothing
// relative). It stops with an impact once d - xi falls below s times its starting value.
// A pair that starts within xi plus round-off (see kAccdTouchingRoundoff) is an impact at t = 0.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "solver/kernels/distance.hpp"
#include "solver/kernels/hd.hpp"

namespace grip::solver::kernels {

struct AccdOptions {
  double min_separation = 0.0;   // xi (m): distances <= xi count as contact
  double t_max = 1.0;            // search [0, t_max] of the linear motion
  double rescaling = 0.1;        // s in (0, 1): stop when d - xi < s (d0 - xi); the paper's 0.1
  int max_iterations = 1000000;  // past this, answer the last safe t as an impact
};

struct AccdResult {
  double toi;      // in [0, t_max]; t_max when no impact
  bool impact;     // an impact (or possible impact) was found at or before t_max
  int iterations;  // distance evaluations after the first
};

// Start distances up to xi + kAccdTouchingRoundoff * m (m: the largest |coordinate| at t = 0)
// count as contact. 2^-44 is 256 eps (eps = 2^-52): rounding the coordinates of a touching pair
// moves it apart by up to sqrt(3) eps m, and the distance kernels err by up to ~30 eps m near
// contact (measured against exact arithmetic on random contacts); in that band ACCD's steps
// follow round-off, not geometry, and a touching pair that moves apart would be a miss.
inline constexpr double kAccdTouchingRoundoff = 0x1p-44;

namespace accd_detail {

// Algorithm 1 on 4 vertices: x0 holds positions at t = 0 (columns), dx the displacements over
// [0, 1] with their mean already removed, max_displacement l_p, distance_sq the squared distance
// of the pair given its 4 vertex positions.
template <typename DistanceSq>
GRIP_HD inline AccdResult additive_ccd(const Eigen::Matrix<double, 3, 4>& x0,
                                       const Eigen::Matrix<double, 3, 4>& dx,
                                       double max_displacement, const AccdOptions& options,
                                       DistanceSq distance_sq) {
  const double xi = options.min_separation;
  const double xi_sq = xi * xi;
  double d_sq = distance_sq(x0);
  // Touching (or within xi) at the start, up to round-off: no motion is safe.
  const double touching = xi + kAccdTouchingRoundoff * x0.cwiseAbs().maxCoeff();
  if (d_sq <= touching * touching) return {0.0, true, 0};
  if (max_displacement == 0.0) return {options.t_max, false, 0};
  double d = std::sqrt(d_sq);
  // (d^2 - xi^2) / (d + xi) is d - xi without cancellation when d is close to xi.
  const double gap = options.rescaling * (d_sq - xi_sq) / (d + xi);
  double t = 0.0;
  for (int iteration = 1; iteration <= options.max_iterations; ++iteration) {
    const double t_l = (1.0 - options.rescaling) * (d_sq - xi_sq) / ((d + xi) * max_displacement);
    // No contact is possible on [t, t + t_l]; past t_max there is nothing left to check.
    if (t + t_l > options.t_max) return {options.t_max, false, iteration - 1};
    // From x0 each time (not accumulated) so round-off does not drift along the path.
    d_sq = distance_sq(x0 + (t + t_l) * dx);
    d = std::sqrt(d_sq);
    // The paper accepts the first step unconditionally (t > 0 guard) so the answer is not 0;
    // a step that round-off brought to (or past) contact is never accepted.
    if (d_sq <= xi_sq || (t > 0.0 && (d_sq - xi_sq) / (d + xi) < gap)) {
      return {t, true, iteration};
    }
    t += t_l;
  }
  return {t, true, options.max_iterations};
}

struct PointTriangleDistanceSq {
  GRIP_HD double operator()(const Eigen::Matrix<double, 3, 4>& v) const {
    return point_triangle_distance_sq(v.col(0), v.col(1), v.col(2), v.col(3));
  }
};

struct EdgeEdgeDistanceSq {
  GRIP_HD double operator()(const Eigen::Matrix<double, 3, 4>& v) const {
    return edge_edge_distance_sq(v.col(0), v.col(1), v.col(2), v.col(3));
  }
};

}  // namespace accd_detail

// l_p of Algorithm 1 for a pair's vertex displacements dx over [0, 1] (columns: the point then
// the triangle's vertices, or the first edge's then the second's), which it leaves less their
// mean (a motion the pair shares moves nothing relative): the fastest vertex of one primitive
// plus the fastest of the other's bounds how fast any two of their points close.
GRIP_HD inline double accd_relative_motion(Eigen::Matrix<double, 3, 4>& dx, bool edge_edge) {
  dx.colwise() -= dx.rowwise().mean();
  if (edge_edge) {
    return std::max(dx.col(0).norm(), dx.col(1).norm()) +
           std::max(dx.col(2).norm(), dx.col(3).norm());
  }
  return dx.col(0).norm() +
         std::max(dx.col(1).norm(), std::max(dx.col(2).norm(), dx.col(3).norm()));
}

// Whether additive CCD of a pair that starts at distance d (beyond min_separation) with relative
// motion bound l_p answers "no impact" at its first advance, without evaluating a distance on the
// path: (1 - s) (d - xi) / l_p already passes t_max. Most pairs whose swept boxes overlap when an
// object falls or flies past a gripper are such (99.6 % of them on a LEAP trial whose cylinder
// slid out), so the broad phase leaves them out of the pairs CCD watches.
GRIP_HD inline bool accd_clears_at_first_advance(double d, double l_p, const AccdOptions& options) {
  return (1.0 - options.rescaling) * (d - options.min_separation) > options.t_max * l_p;
}

// Point p moving p_t0 -> p_t1 against triangle (t0, t1, t2) moving from *_t0 to *_t1.
GRIP_HD inline AccdResult point_triangle_accd(
    const Eigen::Vector3d& p_t0, const Eigen::Vector3d& t0_t0, const Eigen::Vector3d& t1_t0,
    const Eigen::Vector3d& t2_t0, const Eigen::Vector3d& p_t1, const Eigen::Vector3d& t0_t1,
    const Eigen::Vector3d& t1_t1, const Eigen::Vector3d& t2_t1, const AccdOptions& options = {}) {
  Eigen::Matrix<double, 3, 4> x;
  x << p_t0, t0_t0, t1_t0, t2_t0;
  Eigen::Matrix<double, 3, 4> dx;
  dx << p_t1 - p_t0, t0_t1 - t0_t0, t1_t1 - t1_t0, t2_t1 - t2_t0;
  const double l_p = accd_relative_motion(dx, /*edge_edge=*/false);
  return accd_detail::additive_ccd(x, dx, l_p, options, accd_detail::PointTriangleDistanceSq{});
}

// Edge (ea0, ea1) against edge (eb0, eb1), each vertex moving linearly from *_t0 to *_t1.
GRIP_HD inline AccdResult edge_edge_accd(
    const Eigen::Vector3d& ea0_t0, const Eigen::Vector3d& ea1_t0, const Eigen::Vector3d& eb0_t0,
    const Eigen::Vector3d& eb1_t0, const Eigen::Vector3d& ea0_t1, const Eigen::Vector3d& ea1_t1,
    const Eigen::Vector3d& eb0_t1, const Eigen::Vector3d& eb1_t1, const AccdOptions& options = {}) {
  Eigen::Matrix<double, 3, 4> x;
  x << ea0_t0, ea1_t0, eb0_t0, eb1_t0;
  Eigen::Matrix<double, 3, 4> dx;
  dx << ea0_t1 - ea0_t0, ea1_t1 - ea1_t0, eb0_t1 - eb0_t0, eb1_t1 - eb1_t0;
  const double l_p = accd_relative_motion(dx, /*edge_edge=*/true);
  return accd_detail::additive_ccd(x, dx, l_p, options, accd_detail::EdgeEdgeDistanceSq{});
}

}  // namespace grip::solver::kernels
