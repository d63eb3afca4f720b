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

PcgStructure pcg_structure(const FemBatch& fem, const AffineBatch& affine,
                           const BlockPattern& pattern, const std::vector<int>& dof_begin,
                           int aggregate_vertices) {
  const int units = dof_begin.back() / 3;
  PcgStructure s{pattern.row,
                 pattern.column,
                 block_rows(pattern, units),
                 jacobi_blocks(fem, affine, pattern, dof_begin),
                 {},
                 pattern.environment_begin,
                 {},
                 {}};
  const int environments = static_cast<int>(dof_begin.size()) - 1;
  for (int e = 0; e <= environments; ++e) s.unit_begin.push_back(dof_begin[e] / 3);
  s.coarse = coarse_space(fem, aggregate_vertices, units, s.unit_begin);
  for (int e = 0; e < environments; ++e) {
    s.unit_environment.insert(s.unit_environment.end(), s.unit_begin[e + 1] - s.unit_begin[e], e);
  }
  return s;
}

void HostPcg::check_sizes(const std::vector<double>& block, const std::vector<char>& fixed,
                          const std::vector<double>& rhs, const std::vector<double>& tolerance,
                          const std::vector<double>& x) const {
  const std::size_t dofs = 3 * structure_.unit_environment.size();
  if (fixed.size() != dofs || rhs.size() != dofs || x.size() != dofs ||
      tolerance.size() != std::size_t(structure_.environment_count()) ||
      block.size() != 9 * structure_.row.size()) {
    throw std::invalid_argument("HostPcg::solve: arrays do not match the batch");
  }
}

}  // namespace grip::solver::parallel
