#pragma once
// Moving per-primitive derivatives between coordinate sets: pull-back from "edge vector"
// variables (linear combinations of vertices) and scatter from a sub-primitive's vertices.

#include <Eigen/Core>

#include "solver/kernels/hd.hpp"

namespace grip::solver::kernels {

// A function of K vectors r_k = sum_j S(k, j) x_j, with gradient g (3K) in the r's, has gradient
// (S kron I3)^T g in the N stacked vertices x_j.
template <int K, int N>
GRIP_HD inline Eigen::Matrix<double, 3 * N, 1> pull_back_gradient(
    const Eigen::Matrix<double, K, N>& S, const Eigen::Matrix<double, 3 * K, 1>& g) {
  Eigen::Matrix<double, 3 * N, 1> out = Eigen::Matrix<double, 3 * N, 1>::Zero();
  for (int j = 0; j < N; ++j)
    for (int k = 0; k < K; ++k)
      if (S(k, j) != 0.0) out.template segment<3>(3 * j) += S(k, j) * g.template segment<3>(3 * k);
  return out;
}

// The Hessian counterpart: (S kron I3)^T H (S kron I3).
template <int K, int N>
GRIP_HD inline Eigen::Matrix<double, 3 * N, 3 * N> pull_back_hessian(
    const Eigen::Matrix<double, K, N>& S, const Eigen::Matrix<double, 3 * K, 3 * K>& H) {
  Eigen::Matrix<double, 3 * N, 3 * N> out = Eigen::Matrix<double, 3 * N, 3 * N>::Zero();
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j)
      for (int k = 0; k < K; ++k)
        for (int l = 0; l < K; ++l) {
          const double w = S(k, i) * S(l, j);
          if (w != 0.0)
            out.template block<3, 3>(3 * i, 3 * j) += w * H.template block<3, 3>(3 * k, 3 * l);
        }
  return out;
}

// Places the gradient of a sub-primitive with M vertices into the stacked layout of N vertices:
// sub-vertex m is vertex index[m] of the full primitive.
template <int N, int M>
GRIP_HD inline Eigen::Matrix<double, 3 * N, 1> scatter_gradient(
    const Eigen::Matrix<double, 3 * M, 1>& g, const int (&index)[M]) {
  Eigen::Matrix<double, 3 * N, 1> out = Eigen::Matrix<double, 3 * N, 1>::Zero();
  for (int m = 0; m < M; ++m) out.template segment<3>(3 * index[m]) = g.template segment<3>(3 * m);
  return out;
}

template <int N, int M>
GRIP_HD inline Eigen::Matrix<double, 3 * N, 3 * N> scatter_hessian(
    const Eigen::Matrix<double, 3 * M, 3 * M>& H, const int (&index)[M]) {
  Eigen::Matrix<double, 3 * N, 3 * N> out = Eigen::Matrix<double, 3 * N, 3 * N>::Zero();
  for (int m = 0; m < M; ++m)
    for (int n = 0; n < M; ++n)
      out.template block<3, 3>(3 * index[m], 3 * index[n]) = H.template block<3, 3>(3 * m, 3 * n);
  return out;
}

// [v]x, the matrix with [v]x y = v x y.
GRIP_HD inline Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

}  // namespace grip::solver::kernels
