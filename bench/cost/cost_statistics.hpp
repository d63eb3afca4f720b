#pragma once
// The figures of `grip bench cost`: per arm and verdict the mean, median, 90th percentile and
// largest CPU seconds per candidate, in seconds and in reference units, and where the failing
// trials' time went by stage.
#include <array>
#include <limits>
#include <string>
#include <vector>

#include "bench/cost/cost_benchmark.hpp"

namespace grip::bench {

// The value at rank ceil(q n) (1-based, at least 1) of the n values sorted ascending: the
// nearest-rank percentile, always one of the values (for an even n the median is the lower of
// the two middle ones). NaN for no values.
double nearest_rank(std::vector<double> values, double q);

struct CostStatistics {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  int n = 0;
  double mean = nan;
  double median = nan;  // nearest_rank(0.5)
  double p90 = nan;     // nearest_rank(0.9)
  double max = nan;
};

CostStatistics cost_statistics(const std::vector<double>& values);

// The statistics over `reference_seconds`: each figure in reference units (the mean of ratios
// is the ratio of the mean, and ranks do not change under a positive factor).
CostStatistics in_reference_units(const CostStatistics& seconds, double reference_seconds);

// The candidates of one arm with one verdict: "all", "success", "failure" (every failure kind
// together) or a failure kind ("displaced").
struct CostRow {
  std::string arm;
  std::string verdicts;
  CostStatistics cpu;        // CPU s per candidate
  CostStatistics reference;  // the same in reference units
};

// Per arm in the order they ran: "all", "success" and "failure" (where it has candidates), then
// each failure kind present, in io::FailureKind's order.
std::vector<CostRow> cost_rows(const CostResult& result);

// Each stage's share of the runs' CPU seconds summed (kCostStages' order, the protocol last): the
// shares sum to 1, as the protocol's seconds are what the stages leave. NaN for no CPU time.
std::array<double, kCostStages.size()> stage_shares(const std::vector<const CostRun*>& runs);

// The arm's runs whose trial failed.
std::vector<const CostRun*> failing_runs(const CostResult& result, const std::string& arm);

}  // namespace grip::bench
