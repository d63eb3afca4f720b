#include "bench/ccd/ccd_benchmark.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>

#include "bench/ccd/exact_separation.hpp"
#include "src/json/json_text.hpp"

namespace grip::bench {

namespace {

solver::kernels::AccdResult run_accd(const CcdQuery& q, CcdQueryType type,
                                     const solver::kernels::AccdOptions& options) {
  const auto& v = q.vertices;
  return type == CcdQueryType::kVertexFace
             ? solver::kernels::point_triangle_accd(v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7],
                                                    options)
             : solver::kernels::edge_edge_accd(v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7],
                                               options);
}

}  // namespace

CcdBenchmarkResult run_ccd_benchmark(const std::vector<CcdQuery>& queries, CcdQueryType type,
                                     const solver::kernels::AccdOptions& options) {
  // Small sets are swept repeatedly (for at least kMinTime) so the mean is not one cold pass.
  constexpr std::chrono::milliseconds kMinTime(200);
  std::vector<solver::kernels::AccdResult> results(queries.size());
  std::size_t passes = 0;
  const auto start = std::chrono::steady_clock::now();
  auto stop = start;
  do {
    for (std::size_t i = 0; i < queries.size(); ++i) {
      results[i] = run_accd(queries[i], type, options);
    }
    ++passes;
    stop = std::chrono::steady_clock::now();
  } while (!queries.empty() && stop - start < kMinTime);

  CcdBenchmarkResult out;
  out.queries = queries.size();
  if (!queries.empty()) {
    out.ns_per_query = std::chrono::duration<double, std::nano>(stop - start).count() /
                       static_cast<double>(passes * queries.size());
  }
  for (std::size_t i = 0; i < queries.size(); ++i) {
    const solver::kernels::AccdResult& r = results[i];
    const bool collides = collides_in_truth(queries[i]);
    out.collisions += collides;
    out.touching_starts += queries[i].touches_at_start;
    out.false_negatives += collides && !r.impact;
    out.touching_start_false_negatives += queries[i].touches_at_start && !r.impact;
    out.false_positives += !collides && r.impact;
    out.max_iterations = std::max(out.max_iterations, static_cast<std::size_t>(r.iterations));
    // A pair already in contact at t = 0 has no safe time to return (ACCD answers 0).
    if (exactly_separated_at(queries[i], type, 0.0, options.min_separation) &&
        !exactly_separated_at(queries[i], type, r.toi, options.min_separation)) {
      ++out.unsafe_times;
    }
  }
  return out;
}

std::string summary_json(const CcdBenchmarkResult& result) {
  const nlohmann::ordered_json summary = {{"queries", result.queries},
                                          {"false_negatives", result.false_negatives},
                                          {"false_positives", result.false_positives},
                                          {"ns_per_query", result.ns_per_query}};
  return json::compact_text(summary, "%.1f");
}

}  // namespace grip::bench
