#include "solver/parallel/block_pcg.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace grip::solver::parallel {

BlockRows block_rows(const BlockPattern& pattern, int unit_count) {
  BlockRows rows;
  rows.begin.assign(static_cast<std::size_t>(unit_count) + 1, 0);
  const auto blocks = static_cast<int>(pattern.row.size());
  for (int b = 0; b < blocks; ++b) {
    ++rows.begin[pattern.row[b] + 1];
    if (pattern.column[b] != pattern.row[b]) ++rows.begin[pattern.column[b] + 1];
  }
  for (int u = 0; u < unit_count; ++u) rows.begin[u + 1] += rows.begin[u];
  rows.entry.resize(static_cast<std::size_t>(rows.begin.back()));
  std::vector<int> next(rows.begin.begin(), rows.begin.end() - 1);
  for (int b = 0; b < blocks; ++b) {
    rows.entry[next[pattern.row[b]]++] = 2 * b;
    if (pattern.column[b] != pattern.row[b]) rows.entry[next[pattern.column[b]]++] = 2 * b + 1;
  }
  return rows;
}

JacobiBuffers JacobiBlocks::buffers() const {
  return {static_cast<int>(first_unit.size()), first_unit.data(), units.data(),
          matrix_block.data()};
}

namespace {

// The index of block (row, column) in the pattern; throws when the pattern lacks it.
int find_block(const BlockPattern& pattern, int row, int column) {
  const auto key = std::make_pair(row, column);
  int low = 0, high = static_cast<int>(pattern.row.size());
  while (low < high) {  // the first block not before (row, column)
    const int mid = (low + high) / 2;
    if (std::make_pair(pattern.row[mid], pattern.column[mid]) < key) {
      low = mid + 1;
    } else {
      high = mid;
    }
  }
  if (low == static_cast<int>(pattern.row.size()) || pattern.row[low] != row ||
      pattern.column[low] != column) {
    throw std::invalid_argument("jacobi_blocks: the pattern lacks a block within a DOF block");
  }
  return low;
}

}  // namespace

JacobiBlocks jacobi_blocks(const FemBatch& fem, const AffineBatch& affine,
                           const BlockPattern& pattern, const std::vector<int>& dof_begin) {
  std::vector<std::pair<int, int>> dof_blocks;  // (first unit, units)
  for (const int dof : fem.vertex_dof()) dof_blocks.emplace_back(dof / 3, 1);
  for (const int dof : affine.dof()) dof_blocks.emplace_back(dof / 3, 4);
  std::sort(dof_blocks.begin(), dof_blocks.end());
  JacobiBlocks jacobi;
  for (const auto& [first, units] : dof_blocks) {
    jacobi.first_unit.push_back(first);
    jacobi.units.push_back(units);
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j <= i; ++j) {
        jacobi.matrix_block.push_back(i < units ? find_block(pattern, first + i, first + j) : -1);
      }
    }
  }
  for (const int dof : dof_begin) {
    const auto end = std::lower_bound(jacobi.first_unit.begin(), jacobi.first_unit.end(), dof / 3);
    jacobi.environment_begin.push_back(static_cast<int>(end - jacobi.first_unit.begin()));
  }
  return jacobi;
}

HostPcg::HostPcg(const FemBatch& fem, const AffineBatch& affine, const BlockPattern& pattern,
                 const std::vector<int>& dof_begin)
    : pattern_(pattern.buffers()),
      rows_(block_rows(pattern, dof_begin.back() / 3)),
      jacobi_(jacobi_blocks(fem, affine, pattern, dof_begin)) {
  const int environments = static_cast<int>(dof_begin.size()) - 1;
  for (int e = 0; e <= environments; ++e) unit_begin_.push_back(dof_begin[e] / 3);
  for (int e = 0; e < environments; ++e) {
    unit_environment_.insert(unit_environment_.end(), unit_begin_[e + 1] - unit_begin_[e], e);
  }
  const auto dofs = static_cast<std::size_t>(dof_begin.back());
  const auto envs = static_cast<std::size_t>(environments);
  vectors_.assign(4 * dofs, 0.0);
  scalars_.assign(8 * envs, 0.0);
  partial_.assign(dofs / 3, 0.0);
  jacobi_inverse_.assign(144 * jacobi_.first_unit.size(), 0.0);
  jacobi_ok_.assign(jacobi_.first_unit.size(), 0);
  status_.assign(envs, kPcgRunning);
  iterations_.assign(envs, 0);
}

PcgBuffers HostPcg::buffers(const std::vector<double>& block, const std::vector<char>& fixed,
                            const std::vector<double>& rhs, const std::vector<double>& tolerance,
                            int max_iterations, std::vector<double>& x) {
  const std::size_t dofs = partial_.size() * 3;
  if (fixed.size() != dofs || rhs.size() != dofs || x.size() != dofs ||
      tolerance.size() != status_.size() || block.size() != 9 * std::size_t(pattern_.count)) {
    throw std::invalid_argument("HostPcg::solve: arrays do not match the batch");
  }
  PcgBuffers p;
  p.pattern = pattern_;
  p.block = block.data();
  p.rows = rows_.buffers();
  p.jacobi = jacobi_.buffers();
  p.unit_count = static_cast<int>(partial_.size());
  p.unit_environment = unit_environment_.data();
  p.fixed = fixed.data();
  p.environment_count = static_cast<int>(status_.size());
  p.unit_begin = unit_begin_.data();
  p.jacobi_begin = jacobi_.environment_begin.data();
  p.tolerance = tolerance.data();
  p.max_iterations = max_iterations;
  p.status = status_.data();
  p.iterations = iterations_.data();
  p.rhs = rhs.data();
  p.x = x.data();
  p.partial = partial_.data();
  p.jacobi_inverse = jacobi_inverse_.data();
  p.jacobi_ok = jacobi_ok_.data();
  lay_out_pcg_work(p, vectors_.data(), scalars_.data());
  p.running = &running_;
  return p;
}

}  // namespace grip::solver::parallel
