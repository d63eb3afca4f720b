#pragma once
// Axis-aligned bounding boxes: of a primitive over a time step (its swept box), inflated by the
// contact distance d_hat, so that overlapping boxes are exactly the pairs that may come closer
// than d_hat during the step.
#include <Eigen/Core>
#include <limits>

#include "solver/kernels/hd.hpp"

namespace grip::solver {

struct Aabb {
  Eigen::Vector3d min = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d max = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());

  GRIP_HD void expand(const Eigen::Vector3d& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  GRIP_HD void expand(const Aabb& other) {
    min = min.cwiseMin(other.min);
    max = max.cwiseMax(other.max);
  }
  GRIP_HD void inflate(double margin) {
    min.array() -= margin;
    max.array() += margin;
  }
  GRIP_HD bool overlaps(const Aabb& other) const {
    return (min.array() <= other.max.array()).all() && (other.min.array() <= max.array()).all();
  }
  GRIP_HD bool contains(const Aabb& other) const {
    return (min.array() <= other.min.array()).all() && (other.max.array() <= max.array()).all();
  }
  GRIP_HD Eigen::Vector3d center() const { return 0.5 * (min + max); }
  // The squared distance between the two boxes: 0 where they overlap, at most that of any point
  // of one to any point of the other.
  GRIP_HD double distance_sq(const Aabb& other) const {
    const Eigen::Array3d gap =
        (other.min.array() - max.array()).max(min.array() - other.max.array()).max(0.0);
    return gap.matrix().squaredNorm();
  }
};

}  // namespace grip::solver
