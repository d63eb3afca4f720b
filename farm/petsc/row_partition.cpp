#include "farm/petsc/row_partition.hpp"

#include <metis.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace grip::farm {

namespace {

// Which part each block goes to: METIS k-way on the block graph (an edge where any entry
// couples two blocks).
std::vector<idx_t> block_parts(const Eigen::SparseMatrix<double>& lower, int parts,
                               int block_size) {
  const int blocks = static_cast<int>(lower.rows()) / block_size;
  if (parts == 1 || blocks <= parts) {
    std::vector<idx_t> part(blocks);
    for (int b = 0; b < blocks; ++b) part[b] = b * parts / std::max(blocks, 1);
    return part;
  }
  std::vector<std::vector<idx_t>> neighbours(blocks);
  for (int c = 0; c < lower.outerSize(); ++c) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(lower, c); it; ++it) {
      const int a = static_cast<int>(it.row()) / block_size, b = c / block_size;
      if (a == b) continue;
      neighbours[a].push_back(b);
      neighbours[b].push_back(a);
    }
  }
  std::vector<idx_t> xadj(blocks + 1, 0);
  std::vector<idx_t> adjncy;
  for (int b = 0; b < blocks; ++b) {
    std::vector<idx_t>& list = neighbours[b];
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    adjncy.insert(adjncy.end(), list.begin(), list.end());
    xadj[b + 1] = static_cast<idx_t>(adjncy.size());
  }
  idx_t vertices = blocks, constraints = 1, nparts = parts, cut = 0;
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = 1;  // the same partition on every run
  std::vector<idx_t> part(blocks);
  const int status =
      METIS_PartGraphKway(&vertices, &constraints, xadj.data(), adjncy.data(), nullptr, nullptr,
                          nullptr, &nparts, nullptr, nullptr, options, &cut, part.data());
  if (status != METIS_OK) {
    throw std::runtime_error("METIS_PartGraphKway failed with status " + std::to_string(status));
  }
  return part;
}

}  // namespace

RowPartition partition_rows(const Eigen::SparseMatrix<double>& lower, int parts, int block_size) {
  const int n = static_cast<int>(lower.rows());
  if (parts < 1 || block_size < 1 || n % block_size != 0) {
    throw std::invalid_argument("partition_rows: " + std::to_string(n) + " rows in blocks of " +
                                std::to_string(block_size) + " into " + std::to_string(parts) +
                                " parts");
  }
  const std::vector<idx_t> part = block_parts(lower, parts, block_size);
  RowPartition partition;
  partition.row_begin.assign(parts + 1, 0);
  for (const idx_t p : part) partition.row_begin[p + 1] += block_size;
  for (int p = 0; p < parts; ++p) partition.row_begin[p + 1] += partition.row_begin[p];
  std::vector<int> next(partition.row_begin.begin(), partition.row_begin.end() - 1);
  partition.new_of_old.resize(n);
  for (std::size_t b = 0; b < part.size(); ++b) {
    for (int i = 0; i < block_size; ++i) {
      partition.new_of_old[b * block_size + i] = next[part[b]]++;
    }
  }
  return partition;
}

}  // namespace grip::farm
