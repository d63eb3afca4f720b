#include "solver/linear/block_ordering.hpp"

#include <metis.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace grip::solver {

std::vector<int> nested_dissection_ordering(const BlockGraph& graph) {
  const int blocks = static_cast<int>(graph.block_offset.size()) - 1;
  if (blocks <= 0) return {};
  // Blocks coupled to others are dissected; uncoupled ones (affine bodies, pinned vertices) go
  // last, in index order. Contacts, which the graph does not hold, couple an affine body to
  // every vertex it touches: eliminated first, it would join them all in one dense clique;
  // eliminated last, its fill stays in its own 12 rows.
  std::vector<int> coupled, uncoupled;
  std::vector<int> index_in_coupled(static_cast<std::size_t>(blocks), -1);
  std::vector<std::vector<int>> neighbours(static_cast<std::size_t>(blocks));
  for (int b = 0; b < blocks; ++b) {
    std::vector<int>& n = neighbours[static_cast<std::size_t>(b)];
    n = graph.neighbours[static_cast<std::size_t>(b)];
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
    n.erase(std::remove(n.begin(), n.end(), b), n.end());
    if (n.empty()) {
      uncoupled.push_back(b);
    } else {
      index_in_coupled[static_cast<std::size_t>(b)] = static_cast<int>(coupled.size());
      coupled.push_back(b);
    }
  }
  std::vector<int> block_order;
  block_order.reserve(static_cast<std::size_t>(blocks));
  if (!coupled.empty()) {
    std::vector<idx_t> xadj{0};
    std::vector<idx_t> adjncy;
    for (const int b : coupled) {
      for (const int c : neighbours[static_cast<std::size_t>(b)]) {
        adjncy.push_back(index_in_coupled[static_cast<std::size_t>(c)]);
      }
      xadj.push_back(static_cast<idx_t>(adjncy.size()));
    }
    idx_t count = static_cast<idx_t>(coupled.size());
    idx_t options[METIS_NOPTIONS];
    METIS_SetDefaultOptions(options);
    options[METIS_OPTION_SEED] = 0;  // METIS's own default, stated: the ordering is reproducible
    std::vector<idx_t> perm(coupled.size());
    std::vector<idx_t> iperm(coupled.size());
    const int status = METIS_NodeND(&count, xadj.data(), adjncy.data(), nullptr, options,
                                    perm.data(), iperm.data());
    if (status != METIS_OK) {
      throw std::runtime_error("METIS_NodeND failed with status " + std::to_string(status));
    }
    // Row k of the permuted matrix is row perm[k] of the original (METIS manual,
    // METIS_NodeND): perm is new-to-old, the elimination order.
    for (const idx_t k : perm) block_order.push_back(coupled[static_cast<std::size_t>(k)]);
  }
  block_order.insert(block_order.end(), uncoupled.begin(), uncoupled.end());
  std::vector<int> dofs;
  dofs.reserve(static_cast<std::size_t>(graph.block_offset.back()));
  for (int b : block_order) {
    for (int d = graph.block_offset[b]; d < graph.block_offset[b + 1]; ++d) dofs.push_back(d);
  }
  return dofs;
}

}  // namespace grip::solver
