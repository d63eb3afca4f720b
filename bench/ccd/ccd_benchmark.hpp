#pragma once
// Scores additive CCD on a set of benchmark queries: false negatives and positives against the
// ground truth (touching at t = 0 counts as a collision), mean time per query, and how many
// returned times leave the pair not apart.
#include <cstddef>
#include <string>
#include <vector>

#include "bench/ccd/ccd_query.hpp"
#include "solver/kernels/accd.hpp"

namespace grip::bench {

struct CcdBenchmarkResult {
  std::size_t queries = 0;
  std::size_t collisions = 0;                      // by the ground truth, touching starts included
  std::size_t touching_starts = 0;                 // queries whose exact primitives touch at t = 0
  std::size_t false_negatives = 0;                 // truth says collision, ACCD says none
  std::size_t touching_start_false_negatives = 0;  // of them, at touching starts
  std::size_t false_positives = 0;                 // truth says none, ACCD reports an impact
  double ns_per_query = 0.0;  // wall time of ACCD alone, mean over queries and sweeps
  // Queries that start apart (exactly) but whose returned time of impact leaves them not apart,
  // checked in exact arithmetic. Zero for a correct conservative CCD.
  std::size_t unsafe_times = 0;
  std::size_t max_iterations = 0;  // most ACCD iterations any query took
};

// Runs ACCD on every query (timed: the whole set swept for at least 0.2 s), then checks each
// result exactly.
CcdBenchmarkResult run_ccd_benchmark(const std::vector<CcdQuery>& queries, CcdQueryType type,
                                     const solver::kernels::AccdOptions& options);

// {"queries":N,"false_negatives":N,"false_positives":N,"ns_per_query":X}
std::string summary_json(const CcdBenchmarkResult& result);

}  // namespace grip::bench
