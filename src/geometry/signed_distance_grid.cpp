#include "src/geometry/signed_distance_grid.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace grip::geometry {

SignedDistanceGrid::SignedDistanceGrid(std::shared_ptr<const SignedDistance> exact, double spacing,
                                       double padding)
    : exact_(std::move(exact)), spacing_(spacing) {
  if (!exact_) throw std::invalid_argument("signed distance grid: no signed distance given");
  if (!(spacing > 0.0)) {
    throw std::invalid_argument("signed distance grid: the spacing must be positive");
  }
  if (!(padding >= 0.0)) {
    throw std::invalid_argument("signed distance grid: the padding must not be negative");
  }
  const Eigen::Matrix<double, 2, 3> bounds = exact_->bounds();
  origin_ = bounds.row(0).transpose() - Eigen::Vector3d::Constant(padding);
  const Eigen::Vector3d extent = bounds.row(1).transpose() - bounds.row(0).transpose() +
                                 Eigen::Vector3d::Constant(2.0 * padding);
  double nodes = 1.0;
  for (int a = 0; a < 3; ++a) {
    const double cells = std::max(1.0, std::ceil(extent[a] / spacing));
    nodes *= cells + 1.0;
    counts_[a] = static_cast<int>(std::min(cells + 1.0, 1e9));
  }
  if (nodes > static_cast<double>(1 << 28)) {
    throw std::invalid_argument("signed distance grid: spacing " + std::to_string(spacing) +
                                " m would need " + std::to_string(nodes) +
                                " nodes; use a coarser spacing");
  }
  Vertices positions(static_cast<Eigen::Index>(nodes), 3);
  Eigen::Index n = 0;
  for (int k = 0; k < counts_[2]; ++k) {
    for (int j = 0; j < counts_[1]; ++j) {
      for (int i = 0; i < counts_[0]; ++i) {
        positions.row(n++) = (origin_ + spacing * Eigen::Vector3d(i, j, k)).transpose();
      }
    }
  }
  values_ = exact_->evaluate(positions);
}

double SignedDistanceGrid::node_value(int i, int j, int k) const {
  return values_[(static_cast<Eigen::Index>(k) * counts_[1] + j) * counts_[0] + i];
}

bool SignedDistanceGrid::contains(const Eigen::Vector3d& point) const {
  const Eigen::Vector3d local = (point - origin_) / spacing_;
  for (int a = 0; a < 3; ++a) {
    if (!(local[a] >= 0.0 && local[a] <= counts_[a] - 1)) return false;
  }
  return true;
}

double SignedDistanceGrid::operator()(const Eigen::Vector3d& point) const {
  if (!contains(point)) return (*exact_)(point);
  const Eigen::Vector3d local = (point - origin_) / spacing_;
  int cell[3];
  double t[3];
  for (int a = 0; a < 3; ++a) {
    cell[a] = std::min(static_cast<int>(local[a]), counts_[a] - 2);
    t[a] = local[a] - cell[a];
  }
  double value = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    const int di = corner & 1;
    const int dj = (corner >> 1) & 1;
    const int dk = (corner >> 2) & 1;
    const double weight =
        (di ? t[0] : 1.0 - t[0]) * (dj ? t[1] : 1.0 - t[1]) * (dk ? t[2] : 1.0 - t[2]);
    value += weight * node_value(cell[0] + di, cell[1] + dj, cell[2] + dk);
  }
  return value;
}

Eigen::VectorXd SignedDistanceGrid::evaluate(const Vertices& points) const {
  Eigen::VectorXd result(points.rows());
  for (Eigen::Index i = 0; i < points.rows(); ++i) result[i] = (*this)(points.row(i).transpose());
  return result;
}

double SignedDistanceGrid::error_bound() const { return std::sqrt(3.0) / 2.0 * spacing_; }

}  // namespace grip::geometry
