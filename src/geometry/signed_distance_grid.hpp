#pragma once
// A signed distance field cached on a regular grid and interpolated trilinearly, for queries
// that must be fast (millions per trial) more than exact. Same sign convention as
// SignedDistance: positive inside the object.
#include <memory>

#include <Eigen/Core>

#include "src/geometry/signed_distance.hpp"

namespace grip::geometry {

class SignedDistanceGrid {
 public:
  // Samples `exact` at the nodes of a grid with node spacing `spacing` (m) covering the
  // surface's bounding box grown by `padding` (m) on every side. Built once, in parallel;
  // the values do not depend on the number of threads. Throws std::invalid_argument for a
  // non-positive spacing, a negative padding or more than 2^28 nodes.
  SignedDistanceGrid(std::shared_ptr<const SignedDistance> exact, double spacing, double padding);

  // Trilinear interpolation inside the grid; outside it, the exact distance. Thread-safe.
  double operator()(const Eigen::Vector3d& point) const;

  Eigen::VectorXd evaluate(const Vertices& points) const;

  // The signed distance is 1-Lipschitz, so inside the grid the interpolated value differs
  // from the exact one by at most sqrt(3)/2 * spacing (the weighted mean distance from a point
  // to its cell's corners); where the surface is smooth on the cell scale the error is
  // O(spacing^2 / radius of curvature).
  double error_bound() const;

  double spacing() const { return spacing_; }
  Eigen::Vector3i node_counts() const { return counts_; }
  bool contains(const Eigen::Vector3d& point) const;

 private:
  double node_value(int i, int j, int k) const;

  std::shared_ptr<const SignedDistance> exact_;
  double spacing_;
  Eigen::Vector3d origin_;
  Eigen::Vector3i counts_;
  Eigen::VectorXd values_;  // x fastest, then y, then z
};

}  // namespace grip::geometry
