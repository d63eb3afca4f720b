#include "bench/cost/cost_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "io/candidate_record.hpp"

namespace grip::bench {

double nearest_rank(std::vector<double> values, double q) {
  if (values.empty()) return CostStatistics::nan;
  std::sort(values.begin(), values.end());
  const auto n = static_cast<double>(values.size());
  const auto rank =
      std::clamp(static_cast<std::size_t>(std::ceil(q * n)), std::size_t{1}, values.size());
  return values[rank - 1];
}

CostStatistics cost_statistics(const std::vector<double>& values) {
  CostStatistics s;
  s.n = static_cast<int>(values.size());
  if (values.empty()) return s;
  double sum = 0.0;
  for (const double v : values) sum += v;
  s.mean = sum / static_cast<double>(values.size());
  s.median = nearest_rank(values, 0.5);
  s.p90 = nearest_rank(values, 0.9);
  s.max = *std::max_element(values.begin(), values.end());
  return s;
}

CostStatistics in_reference_units(const CostStatistics& seconds, double reference_seconds) {
  CostStatistics r = seconds;
  r.mean /= reference_seconds;
  r.median /= reference_seconds;
  r.p90 /= reference_seconds;
  r.max /= reference_seconds;
  return r;
}

std::vector<CostRow> cost_rows(const CostResult& result) {
  std::vector<CostRow> rows;
  const double reference = result.reference.seconds();
  for (const std::string& arm : result.arms) {
    const auto add = [&](const std::string& verdicts, auto&& keep) {
      std::vector<double> cpu;
      for (const CostRun& run : result.runs) {
        if (run.arm == arm && keep(run.trial)) cpu.push_back(run.cpu_seconds);
      }
      if (cpu.empty() && verdicts != "all") return;
      const CostStatistics s = cost_statistics(cpu);
      rows.push_back({arm, verdicts, s, in_reference_units(s, reference)});
    };
    add("all", [](const RobustnessTrial&) { return true; });
    add("success", [](const RobustnessTrial& t) { return t.failure == io::FailureKind::kNone; });
    add("failure", [](const RobustnessTrial& t) { return t.failure != io::FailureKind::kNone; });
    for (std::uint8_t k = 1; k < io::kFailureKindCount; ++k) {
      const auto kind = static_cast<io::FailureKind>(k);
      add(std::string(io::to_string(kind)),
          [kind](const RobustnessTrial& t) { return t.failure == kind; });
    }
  }
  return rows;
}

std::array<double, kCostStages.size()> stage_shares(const std::vector<const CostRun*>& runs) {
  std::array<double, kCostStages.size()> shares{};
  double wall = 0.0;
  for (const CostRun* run : runs) {
    wall += run->wall_seconds;
    const std::array<double, kCostStages.size()> seconds = run->stage_seconds();
    for (std::size_t i = 0; i < shares.size(); ++i) shares[i] += seconds[i];
  }
  for (double& share : shares) share = wall > 0 ? share / wall : CostStatistics::nan;
  return shares;
}

std::vector<const CostRun*> failing_runs(const CostResult& result, const std::string& arm) {
  std::vector<const CostRun*> runs;
  for (const CostRun& run : result.runs) {
    if (run.arm == arm && run.trial.failure != io::FailureKind::kNone) runs.push_back(&run);
  }
  return runs;
}

}  // namespace grip::bench
