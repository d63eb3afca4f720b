#pragma once
// The four collision vertices of a contact stencil, gathered from a position array.
#include <Eigen/Core>
#include <array>

#include "solver/scene/scene.hpp"

namespace grip::solver {

inline void gather(const Vertices& positions, const std::array<int, 4>& vertex,
                   Eigen::Vector3d x[4]) {
  for (int i = 0; i < 4; ++i) x[i] = positions.row(vertex[i]);
}

inline Eigen::Matrix<double, 12, 1> stack(const Eigen::Vector3d x[4]) {
  Eigen::Matrix<double, 12, 1> s;
  for (int i = 0; i < 4; ++i) s.segment<3>(3 * i) = x[i];
  return s;
}

}  // namespace grip::solver
