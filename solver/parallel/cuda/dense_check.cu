#include "solver/parallel/cuda/dense_check.cuh"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <vector>

#include "solver/parallel/cuda/cuda_launcher.cuh"
#include "solver/parallel/cuda/relative_difference.cuh"
#include "solver/parallel/dense_cholesky.hpp"
#include "solver/parallel/launch.hpp"

namespace grip::solver::parallel {
namespace {

constexpr int kBodies = 17;
constexpr int kUnits = 4 * kBodies;  // per environment
constexpr int kDofs = 3 * kUnits;

struct DenseScene {
  std::vector<int> dof_begin, block_begin, row, column;
  std::vector<double> block, rhs, x;
  std::vector<char> fixed;
  std::vector<long long> matrix_begin;
};

// One 3x3 block (row unit r, column unit c; r >= c): random entries in [-1, 1], and on the
// diagonal (r == c) symmetric with 40 added: every row's diagonal dominates its at most 18
// other entries.
void add_block(DenseScene& s, int r, int c, std::uint64_t& seed) {
  double b[9];
  for (double& v : b) {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    v = 2.0 * static_cast<double>(seed >> 11) / static_cast<double>(1ull << 53) - 1.0;
  }
  if (r == c) {
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < i; ++j) b[3 * i + j] = b[3 * j + i];
      b[4 * i] += 40.0;
    }
  }
  s.row.push_back(r);
  s.column.push_back(c);
  s.block.insert(s.block.end(), b, b + 9);
}

DenseScene dense_scene(int environments) {
  DenseScene s;
  std::uint64_t seed = 0x2545f4914f6cdd1dull;
  s.dof_begin.push_back(0);
  s.block_begin.push_back(0);
  for (int e = 0; e < environments; ++e) {
    const int first = e * kUnits;
    for (int body = 0; body < kBodies; ++body) {
      for (int i = 0; i < 4; ++i) {
        for (int j = 0; j <= i; ++j) add_block(s, first + 4 * body + i, first + 4 * body + j, seed);
      }
      if (body > 0) add_block(s, first + 4 * body, first + 4 * (body - 1), seed);
    }
    s.dof_begin.push_back(s.dof_begin.back() + kDofs);
    s.block_begin.push_back(static_cast<int>(s.row.size()));
  }
  const std::size_t dofs = std::size_t(s.dof_begin.back());
  s.fixed.assign(dofs, 0);
  s.rhs.resize(dofs);
  s.x.assign(dofs, 0.0);
  for (std::size_t d = 0; d < dofs; ++d) {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    s.rhs[d] = static_cast<double>(seed >> 11) / static_cast<double>(1ull << 53);
    if (d % kDofs < 3) {
      s.fixed[d] = 1;
      s.x[d] = 0.01 * s.rhs[d];
    }
  }
  s.matrix_begin = dense_matrix_begin(s.dof_begin);
  return s;
}

}  // namespace

DenseCheck check_dense_cholesky(int environments, int repeats) {
  const DenseScene s = dense_scene(environments);
  DenseCheck check;
  check.dofs = kDofs;
  std::vector<double> matrix(std::size_t(s.matrix_begin.back())), host_x = s.x;
  std::vector<int> host_status(static_cast<std::size_t>(environments));
  const auto start = std::chrono::steady_clock::now();
  SerialLauncher{}(environments,
                   DenseCholeskyStage{{environments, s.dof_begin.data(), s.block_begin.data(),
                                       s.row.data(), s.column.data(), s.block.data(),
                                       s.fixed.data(), s.rhs.data(), s.matrix_begin.data(),
                                       matrix.data(), host_x.data(), host_status.data()}});
  check.host_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  const DeviceArray<int> dof_begin(s.dof_begin), block_begin(s.block_begin), row(s.row),
      column(s.column);
  const DeviceArray<double> block(s.block), rhs(s.rhs);
  const DeviceArray<char> fixed(s.fixed);
  const DeviceArray<long long> matrix_begin(s.matrix_begin);
  DeviceArray<double> device_matrix(matrix.size()), x(s.x);
  DeviceArray<int> status(host_status.size());
  check.device_ms = device_median_ms(repeats, [&] {
    cuda_check(
        cudaMemcpy(x.data(), s.x.data(), s.x.size() * sizeof(double), cudaMemcpyHostToDevice),
        "cudaMemcpy to the device");
    CudaLauncher{}(
        environments,
        DenseCholeskyStage{{environments, dof_begin.data(), block_begin.data(), row.data(),
                            column.data(), block.data(), fixed.data(), rhs.data(),
                            matrix_begin.data(), device_matrix.data(), x.data(), status.data()}});
  });
  check.solution = relative_difference(x.to_host(), host_x, kDofs);
  const std::vector<int> device_status = status.to_host();
  check.all_solved = std::all_of(host_status.begin(), host_status.end(),
                                 [](int v) { return v == kDenseSolved; }) &&
                     device_status == host_status;
  return check;
}

}  // namespace grip::solver::parallel
