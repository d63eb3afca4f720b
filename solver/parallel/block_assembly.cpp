#include "solver/parallel/block_assembly.hpp"

#include <algorithm>
#include <array>

namespace grip::solver::parallel {

BlockPatternBuffers BlockPattern::buffers() const {
  return {static_cast<int>(row.size()),
          row.data(),
          column.data(),
          begin.data(),
          term_slots.data(),
          term_units.data()};
}

BlockPattern contact_block_pattern(const CollisionBatch& batch, const int* pair_vertex,
                                   int pair_count) {
  // Every term as (row, column, term number), sorted by block then term number: a stable order.
  struct Term {
    int row, column, slot_a, slot_b, unit_a, unit_b;
  };
  std::vector<Term> terms;
  const std::vector<int>& block = batch.block();
  for (int k = 0; k < pair_count; ++k) {
    for (int a = 0; a < 4; ++a) {
      const int va = pair_vertex[4 * k + a], ba = block[static_cast<std::size_t>(va)];
      if (ba < 0) continue;
      for (int b = 0; b < 4; ++b) {
        const int vb = pair_vertex[4 * k + b], bb = block[static_cast<std::size_t>(vb)];
        if (bb < 0) continue;
        const int units_a = batch.block_size()[static_cast<std::size_t>(ba)] / 3;
        const int units_b = batch.block_size()[static_cast<std::size_t>(bb)] / 3;
        for (int ua = 0; ua < units_a; ++ua) {
          for (int ub = 0; ub < units_b; ++ub) {
            const int row = batch.block_dof()[static_cast<std::size_t>(ba)] / 3 + ua;
            const int column = batch.block_dof()[static_cast<std::size_t>(bb)] / 3 + ub;
            if (row >= column) terms.push_back({row, column, 4 * k + a, 4 * k + b, ua, ub});
          }
        }
      }
    }
  }
  std::stable_sort(terms.begin(), terms.end(), [](const Term& x, const Term& y) {
    return x.row != y.row ? x.row < y.row : x.column < y.column;
  });
  BlockPattern pattern;
  pattern.begin.push_back(0);
  for (std::size_t t = 0; t < terms.size(); ++t) {
    if (t == 0 || terms[t].row != terms[t - 1].row || terms[t].column != terms[t - 1].column) {
      if (t > 0) pattern.begin.push_back(static_cast<int>(t));
      pattern.row.push_back(terms[t].row);
      pattern.column.push_back(terms[t].column);
    }
    pattern.term_slots.insert(pattern.term_slots.end(), {terms[t].slot_a, terms[t].slot_b});
    pattern.term_units.insert(pattern.term_units.end(), {terms[t].unit_a, terms[t].unit_b});
  }
  if (!terms.empty()) pattern.begin.push_back(static_cast<int>(terms.size()));
  // Blocks by environment: a block's row unit lies in its environment's DOFs.
  pattern.environment_begin.push_back(0);
  std::size_t b = 0;
  for (int e = 0; e < batch.environment_count(); ++e) {
    const int end_unit = batch.dof_begin()[static_cast<std::size_t>(e) + 1] / 3;
    while (b < pattern.row.size() && pattern.row[b] < end_unit) ++b;
    pattern.environment_begin.push_back(static_cast<int>(b));
  }
  return pattern;
}

}  // namespace grip::solver::parallel
