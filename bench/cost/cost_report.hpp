#pragma once
// What `grip bench cost` reports: per arm the CPU seconds per candidate by verdict, in seconds
// and in reference units, and the failing trials' time by stage, as Markdown tables, cost.md,
// cost.csv (one row per candidate) and one JSON line.
#include <filesystem>
#include <ostream>
#include <vector>

#include "bench/cost/cost_benchmark.hpp"
#include "bench/cost/cost_statistics.hpp"

namespace grip::bench {

// The cost table (rows as cost_rows gives them), Markdown.
void write_cost_table(std::ostream& out, const std::vector<CostRow>& rows);
// cost.md (models, the cost and stage tables, setup, the reference and the machine, skipped
// seeds and shortfalls) and cost.csv in `out`, created if missing.
void write_cost_files(const std::filesystem::path& out, const CostResult& result,
                      const std::vector<CostRow>& rows);
// One line of JSON: benchmark, models, candidates, reference_seconds (and its start and end
// medians, grid), wall_seconds; per arm each row's candidates, cpu_seconds and reference_units
// (mean, median, p90, max), and failing_stage_shares; skipped_seeds, shortfalls.
void write_cost_json_line(std::ostream& out, const CostResult& result,
                          const std::vector<CostRow>& rows);

}  // namespace grip::bench
