#include "solver/linear/block_ordering.hpp"

#include <metis.h>

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

namespace grip::solver {

std::vector<int> nested_dissection_ordering(const BlockGraph& graph) {
  const int blocks = static_cast<int>(graph.block_offset.size()) - 1;
  if (blocks <= 0) return {};
  std::vector<int> block_order(static_cast<std::size_t>(blocks));
  std::iota(block_order.begin(), block_order.end(), 0);

  std::vector<idx_t> xadj{0};
  std::vector<idx_t> adjncy;
  for (int b = 0; b < blocks; ++b) {
    std::vector<int> n = graph.neighbours[static_cast<std::size_t>(b)];
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
    for (int c : n) {
      if (c != b) adjncy.push_back(c);
    }
    xadj.push_back(static_cast<idx_t>(adjncy.size()));
  }
  // METIS needs edges to dissect; a graph of isolated blocks is already ordered.
  if (!adjncy.empty()) {
    idx_t count = blocks;
    idx_t options[METIS_NOPTIONS];
    METIS_SetDefaultOptions(options);
    options[METIS_OPTION_SEED] = 0;  // METIS's own default, stated: the ordering is reproducible
    std::vector<idx_t> perm(static_cast<std::size_t>(blocks));
    std::vector<idx_t> iperm(static_cast<std::size_t>(blocks));
    const int status = METIS_NodeND(&count, xadj.data(), adjncy.data(), nullptr, options,
                                    perm.data(), iperm.data());
    if (status != METIS_OK) {
      throw std::runtime_error("METIS_NodeND failed with status " + std::to_string(status));
    }
    // Row k of the permuted matrix is row perm[k] of the original (METIS manual,
    // METIS_NodeND): perm is new-to-old, the elimination order.
    std::copy(perm.begin(), perm.end(), block_order.begin());
  }
  std::vector<int> dofs;
  dofs.reserve(static_cast<std::size_t>(graph.block_offset.back()));
  for (int b : block_order) {
    for (int d = graph.block_offset[b]; d < graph.block_offset[b + 1]; ++d) dofs.push_back(d);
  }
  return dofs;
}

}  // namespace grip::solver
