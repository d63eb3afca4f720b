// The generated hard CCD query set, written in the benchmark's CSV format and read back, scored
// with additive CCD: no false negatives (touching at t = 0 is a collision, answered t = 0), and
// every returned time of impact leaves the pair apart, checked in exact rational arithmetic.
#include "bench/ccd/hard_ccd_queries.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>
#include <ostream>

#include "bench/ccd/ccd_benchmark.hpp"
#include "bench/ccd/ccd_query_file.hpp"
#include "bench/ccd/exact_separation.hpp"

namespace {

using grip::bench::CcdQuery;
using grip::bench::CcdQueryType;
using grip::solver::kernels::AccdOptions;
using grip::solver::kernels::AccdResult;

AccdResult accd(const CcdQuery& q, CcdQueryType type, const AccdOptions& options) {
  const auto& v = q.vertices;
  return type == CcdQueryType::kVertexFace
             ? grip::solver::kernels::point_triangle_accd(v[0], v[1], v[2], v[3], v[4], v[5], v[6],
                                                          v[7], options)
             : grip::solver::kernels::edge_edge_accd(v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7],
                                                     options);
}

}  // namespace

namespace grip::bench {
void PrintTo(CcdQueryType type, std::ostream* out) {
  *out << (type == CcdQueryType::kVertexFace ? "vertex-face" : "edge-edge");
}
}  // namespace grip::bench

namespace {

class HardCcdQueries : public ::testing::TestWithParam<CcdQueryType> {
 protected:
  // The set as the benchmark runner sees it: written to CSV, read back.
  std::vector<CcdQuery> written_and_read() const {
    const auto rational = grip::bench::hard_ccd_queries(GetParam());
    const auto dir = std::filesystem::path(::testing::TempDir()) / "grip_hard_ccd_queries";
    std::filesystem::create_directories(dir);
    const auto path = dir / (GetParam() == CcdQueryType::kVertexFace ? "vf.csv" : "ee.csv");
    grip::bench::write_ccd_query_file(path, rational);
    std::vector<CcdQuery> queries = grip::bench::read_ccd_query_file(path, GetParam());
    EXPECT_EQ(queries.size(), rational.size());
    for (std::size_t i = 0; i < queries.size() && i < rational.size(); ++i) {
      const CcdQuery direct = grip::bench::to_double_query(rational[i]);
      EXPECT_EQ(queries[i].vertices, direct.vertices) << "query " << i;
      EXPECT_EQ(queries[i].collides, direct.collides) << "query " << i;
    }
    return queries;
  }
};

TEST_P(HardCcdQueries, SetIsLargeAndMixed) {
  const auto queries = grip::bench::hard_ccd_queries(GetParam());
  std::size_t hits = 0;
  for (const auto& q : queries) hits += q.collides;
  EXPECT_GE(queries.size(), 200u);
  EXPECT_GE(hits, queries.size() / 3);
  EXPECT_GE(queries.size() - hits, queries.size() / 5);
}

// Every query whose exact primitives touch at t = 0 is labelled a collision, and the set has
// such queries that rounding to double moved apart (the case a CCD must still answer t = 0).
TEST_P(HardCcdQueries, TouchingStartsAreLabelledCollisions) {
  std::size_t touching = 0, rounded_apart = 0;
  for (const CcdQuery& q : written_and_read()) {
    if (!q.touches_at_start) continue;
    ++touching;
    EXPECT_TRUE(q.collides);
    rounded_apart += grip::bench::exactly_separated_at(q, GetParam(), 0.0, 0.0);
  }
  EXPECT_GE(touching, 50u);
  EXPECT_GE(rounded_apart, 10u);
}

// A necessary condition on the labels, checked independently of ACCD: a query labelled a miss
// is exactly apart at 129 evenly spaced times of [0, 1].
TEST_P(HardCcdQueries, MissesAreApartAtSampledTimes) {
  for (const CcdQuery& q : written_and_read()) {
    if (q.collides) continue;
    for (int k = 0; k <= 128; ++k) {
      ASSERT_TRUE(grip::bench::exactly_separated_at(q, GetParam(), k / 128.0, 0.0))
          << "t = " << k / 128.0;
    }
  }
}

TEST_P(HardCcdQueries, NoFalseNegativesAndEveryTimeOfImpactIsSafe) {
  const std::vector<CcdQuery> queries = written_and_read();
  const AccdOptions options;  // minimum separation 0, s = 0.1, t_max = 1
  for (std::size_t i = 0; i < queries.size(); ++i) {
    const AccdResult r = accd(queries[i], GetParam(), options);
    ASSERT_GE(r.toi, 0.0);
    ASSERT_LE(r.toi, 1.0);
    EXPECT_TRUE(r.impact || !grip::bench::collides_in_truth(queries[i]))
        << "false negative, query " << i;
    if (queries[i].touches_at_start) {
      EXPECT_TRUE(r.impact && r.toi == 0.0) << "query " << i << " touches at t = 0 (exactly)";
    }
    if (grip::bench::exactly_separated_at(queries[i], GetParam(), 0.0, 0.0)) {
      EXPECT_TRUE(grip::bench::exactly_separated_at(queries[i], GetParam(), r.toi, 0.0))
          << "query " << i << ": not apart at the returned toi " << r.toi;
    } else {
      EXPECT_EQ(r.toi, 0.0) << "query " << i << " touches at t = 0";
    }
  }
  const grip::bench::CcdBenchmarkResult summary =
      grip::bench::run_ccd_benchmark(queries, GetParam(), options);
  EXPECT_EQ(summary.queries, queries.size());
  EXPECT_EQ(summary.false_negatives, 0u);
  EXPECT_EQ(summary.touching_start_false_negatives, 0u);
  EXPECT_EQ(summary.unsafe_times, 0u);
  // The figures the documentation reports (not asserted: speed is the benchmark's business).
  std::cout << (GetParam() == CcdQueryType::kVertexFace ? "vf " : "ee ")
            << grip::bench::summary_json(summary) << '\n';
}

TEST_P(HardCcdQueries, MinimumSeparationIsKeptExactly) {
  AccdOptions options;
  options.min_separation = 1e-9;
  for (const CcdQuery& q : written_and_read()) {
    if (!grip::bench::exactly_separated_at(q, GetParam(), 0.0, options.min_separation)) continue;
    const AccdResult r = accd(q, GetParam(), options);
    EXPECT_TRUE(grip::bench::exactly_separated_at(q, GetParam(), r.toi, options.min_separation))
        << "toi " << r.toi;
    EXPECT_TRUE(r.impact || !q.collides) << "false negative";
  }
}

INSTANTIATE_TEST_SUITE_P(Types, HardCcdQueries,
                         ::testing::Values(CcdQueryType::kVertexFace, CcdQueryType::kEdgeEdge),
                         [](const ::testing::TestParamInfo<CcdQueryType>& info) {
                           return std::string(info.param == CcdQueryType::kVertexFace ? "VertexFace"
                                                                                      : "EdgeEdge");
                         });

}  // namespace
