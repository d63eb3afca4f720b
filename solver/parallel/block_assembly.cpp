#include "solver/parallel/block_assembly.hpp"

#include <algorithm>

namespace grip::solver::parallel {

void StencilSlots::add(int block_dof, int block_size, double x, double y, double z) {
  dof.push_back(block_dof);
  size.push_back(block_size);
  rest.insert(rest.end(), {x, y, z});
}

void add_tet_stencils(const FemBatch& fem, StencilSlots& slots) {
  for (const int dof : fem.tet_dofs()) slots.add(dof, 3, 0.0, 0.0, 0.0);
}

void add_affine_stencils(const AffineBatch& affine, StencilSlots& slots) {
  for (const int dof : affine.dof()) {
    for (int unit = 0; unit < 4; ++unit) slots.add(dof + 3 * unit, 3, 0.0, 0.0, 0.0);
  }
}

void add_contact_stencils(const CollisionBatch& collision, const int* pair_vertex, int pair_count,
                          StencilSlots& slots) {
  for (int s = 0; s < 4 * pair_count; ++s) {
    const auto v = static_cast<std::size_t>(pair_vertex[s]);
    const int block = collision.block()[v];
    if (block < 0) {
      slots.add(-1, 0, 0.0, 0.0, 0.0);
      continue;
    }
    const auto b = static_cast<std::size_t>(block);
    slots.add(collision.block_dof()[b], collision.block_size()[b], collision.rest()[3 * v],
              collision.rest()[3 * v + 1], collision.rest()[3 * v + 2]);
  }
}

BlockPatternBuffers BlockPattern::buffers() const {
  return {static_cast<int>(row.size()),
          row.data(),
          column.data(),
          begin.data(),
          term_slots.data(),
          term_units.data()};
}

std::vector<int> BlockPattern::diagonal_blocks(const std::vector<int>& units) const {
  std::vector<int> diagonal;
  diagonal.reserve(units.size());
  for (const int unit : units) {
    // Blocks are sorted by (row, column): the diagonal one is the last of its row.
    const auto end = std::upper_bound(row.begin(), row.end(), unit);
    const bool found =
        end != row.begin() && *(end - 1) == unit && column[end - row.begin() - 1] == unit;
    diagonal.push_back(found ? static_cast<int>(end - row.begin() - 1) : -1);
  }
  return diagonal;
}

BlockPattern block_pattern(const StencilSlots& slots, const std::vector<int>& dof_begin) {
  struct Term {
    int row, column, slot_a, slot_b, unit_a, unit_b;
  };
  std::vector<Term> terms;
  for (int s = 0; s < slots.stencil_count(); ++s) {
    for (int a = 4 * s; a < 4 * s + 4; ++a) {
      if (slots.dof[a] < 0) continue;
      for (int b = 4 * s; b < 4 * s + 4; ++b) {
        if (slots.dof[b] < 0) continue;
        for (int ua = 0; ua < slots.size[a] / 3; ++ua) {
          for (int ub = 0; ub < slots.size[b] / 3; ++ub) {
            const int row = slots.dof[a] / 3 + ua, column = slots.dof[b] / 3 + ub;
            if (row >= column) terms.push_back({row, column, a, b, ua, ub});
          }
        }
      }
    }
  }
  // By block, and within a block in the order listed: a stable order.
  std::stable_sort(terms.begin(), terms.end(), [](const Term& x, const Term& y) {
    return x.row != y.row ? x.row < y.row : x.column < y.column;
  });
  BlockPattern pattern;
  for (std::size_t t = 0; t < terms.size(); ++t) {
    if (t == 0 || terms[t].row != terms[t - 1].row || terms[t].column != terms[t - 1].column) {
      pattern.begin.push_back(static_cast<int>(t));
      pattern.row.push_back(terms[t].row);
      pattern.column.push_back(terms[t].column);
    }
    pattern.term_slots.insert(pattern.term_slots.end(), {terms[t].slot_a, terms[t].slot_b});
    pattern.term_units.insert(pattern.term_units.end(), {terms[t].unit_a, terms[t].unit_b});
  }
  pattern.begin.push_back(static_cast<int>(terms.size()));
  // Blocks by environment: a block's row unit lies in its environment's DOFs.
  pattern.environment_begin.push_back(0);
  std::size_t b = 0;
  for (std::size_t e = 1; e < dof_begin.size(); ++e) {
    while (b < pattern.row.size() && pattern.row[b] < dof_begin[e] / 3) ++b;
    pattern.environment_begin.push_back(static_cast<int>(b));
  }
  return pattern;
}

}  // namespace grip::solver::parallel
