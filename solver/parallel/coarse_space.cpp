#include "solver/parallel/coarse_space.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace grip::solver::parallel {

namespace {

// The FEM vertices' units (DOF / 3) in aggregates of up to `size`: each grown breadth-first
// through shared tets from the lowest unit not yet taken, so its lowest unit is its seed and
// the aggregates come in the order of their first units. Tets never span bodies or
// environments, so neither does an aggregate.
std::vector<std::vector<int>> fem_aggregates(const FemBatch& fem, int size, int unit_count) {
  std::vector<std::vector<int>> neighbours(static_cast<std::size_t>(unit_count));
  const std::vector<int>& tet_dofs = fem.tet_dofs();
  for (std::size_t t = 0; t < tet_dofs.size(); t += 4) {
    for (int a = 0; a < 4; ++a) {
      for (int b = 0; b < 4; ++b) {
        if (a != b) neighbours[tet_dofs[t + a] / 3].push_back(tet_dofs[t + b] / 3);
      }
    }
  }
  for (std::vector<int>& list : neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  std::vector<char> taken(neighbours.size(), 0);
  std::vector<std::vector<int>> aggregates;
  for (const int dof : fem.vertex_dof()) {  // ascending
    const int seed = dof / 3;
    if (taken[seed]) continue;
    taken[seed] = 1;
    std::vector<int> aggregate{seed};
    for (std::size_t k = 0; k < aggregate.size(); ++k) {
      for (const int next : neighbours[aggregate[k]]) {
        if (static_cast<int>(aggregate.size()) == size) break;
        if (!taken[next]) {
          taken[next] = 1;
          aggregate.push_back(next);
        }
      }
    }
    std::sort(aggregate.begin(), aggregate.end());
    aggregates.push_back(std::move(aggregate));
  }
  return aggregates;
}

}  // namespace

CoarseSpace coarse_space(const FemBatch& fem, int vertices, int unit_count,
                         const std::vector<int>& unit_begin) {
  if (vertices < 0) throw std::invalid_argument("coarse_space: negative aggregate size");
  CoarseSpace c;
  c.unit_aggregate.assign(static_cast<std::size_t>(unit_count), -1);
  const std::vector<std::vector<int>> aggregates =
      vertices > 0 ? fem_aggregates(fem, vertices, unit_count) : std::vector<std::vector<int>>{};
  std::vector<int> first_unit;
  for (const std::vector<int>& aggregate : aggregates) {
    for (const int unit : aggregate) c.unit_aggregate[unit] = c.aggregate_count();
    c.aggregate_unit.insert(c.aggregate_unit.end(), aggregate.begin(), aggregate.end());
    c.aggregate_unit_begin.push_back(static_cast<int>(c.aggregate_unit.size()));
    first_unit.push_back(aggregate.front());
  }
  c.matrix_begin.push_back(0);
  for (const int unit : unit_begin) {
    const auto end = std::lower_bound(first_unit.begin(), first_unit.end(), unit);
    c.aggregate_begin.push_back(static_cast<int>(end - first_unit.begin()));
    if (c.aggregate_begin.size() < 2) continue;
    const long long n =
        3LL * (c.aggregate_begin.back() - c.aggregate_begin[c.aggregate_begin.size() - 2]);
    c.matrix_begin.push_back(c.matrix_begin.back() + n * n);
  }
  return c;
}

}  // namespace grip::solver::parallel
