#pragma once
// Coordinates of the closest points on the lines or plane of a contact pair, from the lagged
// positions; they weight the vertices in the relative velocity of friction.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "solver/kernels/hd.hpp"

namespace grip::solver::kernels {

// alpha with foot point e0 + alpha (e1 - e0) of p on the edge's line (e0 != e1).
GRIP_HD inline double point_edge_closest_point(const Eigen::Vector3d& p, const Eigen::Vector3d& e0,
                                               const Eigen::Vector3d& e1) {
  const Eigen::Vector3d e = e1 - e0;
  return (p - e0).dot(e) / e.squaredNorm();
}

// (beta1, beta2) with foot point t0 + beta1 (t1 - t0) + beta2 (t2 - t0) of p on the triangle's
// plane: the 2x2 normal equations [a.a a.b; a.b b.b] beta = [a.w; b.w], w = p - t0 (Cramer's rule;
// the triangle must be non-degenerate).
GRIP_HD inline Eigen::Vector2d point_triangle_closest_point(const Eigen::Vector3d& p,
                                                            const Eigen::Vector3d& t0,
                                                            const Eigen::Vector3d& t1,
                                                            const Eigen::Vector3d& t2) {
  const Eigen::Vector3d a = t1 - t0, b = t2 - t0, w = p - t0;
  const double aa = a.squaredNorm(), bb = b.squaredNorm(), ab = a.dot(b);
  const double aw = a.dot(w), bw = b.dot(w);
  const double det = a.cross(b).squaredNorm();
  return Eigen::Vector2d((bb * aw - ab * bw) / det, (aa * bw - ab * aw) / det);
}

// (alpha, beta) with closest points ea0 + alpha (ea1 - ea0) and eb0 + beta (eb1 - eb0) of the two
// lines (they must not be parallel).
GRIP_HD inline Eigen::Vector2d edge_edge_closest_point(const Eigen::Vector3d& ea0,
                                                       const Eigen::Vector3d& ea1,
                                                       const Eigen::Vector3d& eb0,
                                                       const Eigen::Vector3d& eb1) {
  const Eigen::Vector3d a = ea1 - ea0, b = eb1 - eb0, w = ea0 - eb0;
  const double aa = a.squaredNorm(), bb = b.squaredNorm(), ab = a.dot(b);
  const double aw = a.dot(w), bw = b.dot(w);
  const double det = a.cross(b).squaredNorm();
  return Eigen::Vector2d((ab * bw - bb * aw) / det, (aa * bw - ab * aw) / det);
}

}  // namespace grip::solver::kernels
