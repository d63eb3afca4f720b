#pragma once
// Projection of a symmetric matrix onto the positive semi-definite cone (nearest PSD matrix in
// the Frobenius norm): eigen-decompose and clamp negative eigenvalues to zero, as projected
// Newton does per element before assembly.

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>

namespace grip::solver::kernels {

// A matrix with no negative eigenvalue is returned bit-for-bit unchanged.
// Host only, unlike the other kernels: Eigen 3.4's SelfAdjointEigenSolver reaches host-only
// product kernels (nvcc 13 reports them even for N = 3), so a device backend needs its own
// batched symmetric eigen-solver (e.g. cuSOLVER's syevjBatched) for this step.
template <int N>
inline Eigen::Matrix<double, N, N> project_to_psd(const Eigen::Matrix<double, N, N>& H) {
  // Most element Hessians are positive definite already; a Cholesky factorization proves it
  // at a tenth of the eigen-decomposition's cost.
  if (Eigen::LLT<Eigen::Matrix<double, N, N>>(H).info() == Eigen::Success) return H;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> eig(H);
  if (eig.eigenvalues().minCoeff() >= 0.0) return H;
  const Eigen::Matrix<double, N, 1> clamped = eig.eigenvalues().cwiseMax(0.0);
  return eig.eigenvectors() * clamped.asDiagonal() * eig.eigenvectors().transpose();
}

}  // namespace grip::solver::kernels
