// Google Benchmark timings of additive CCD per query type, on the generated hard query set
// (mixed hits, misses, near misses and exact contacts) and on random unit-scale motions.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "bench/ccd/hard_ccd_queries.hpp"
#include "solver/kernels/accd.hpp"

namespace {

using grip::bench::CcdQuery;
using grip::bench::CcdQueryType;

std::vector<CcdQuery> hard_set(CcdQueryType type) {
  std::vector<CcdQuery> out;
  for (const auto& q : grip::bench::hard_ccd_queries(type)) out.push_back(to_double_query(q));
  return out;
}

// Vertices in [-1, 1]^3 displaced by up to 2 per axis: about half of them collide.
std::vector<CcdQuery> random_set(std::size_t count) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<CcdQuery> out(count);
  for (CcdQuery& q : out) {
    for (int i = 0; i < 4; ++i) {
      q.vertices[i] = Eigen::Vector3d(u(rng), u(rng), u(rng));
      q.vertices[i + 4] = q.vertices[i] + 2.0 * Eigen::Vector3d(u(rng), u(rng), u(rng));
    }
  }
  return out;
}

void run(benchmark::State& state, const std::vector<CcdQuery>& queries, CcdQueryType type) {
  const grip::solver::kernels::AccdOptions options;
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& v = queries[i].vertices;
    const auto r = type == CcdQueryType::kVertexFace
                       ? grip::solver::kernels::point_triangle_accd(v[0], v[1], v[2], v[3], v[4],
                                                                    v[5], v[6], v[7], options)
                       : grip::solver::kernels::edge_edge_accd(v[0], v[1], v[2], v[3], v[4], v[5],
                                                               v[6], v[7], options);
    benchmark::DoNotOptimize(r);
    i = i + 1 == queries.size() ? 0 : i + 1;
  }
}

void BM_AccdVertexFaceHard(benchmark::State& state) {
  static const std::vector<CcdQuery> queries = hard_set(CcdQueryType::kVertexFace);
  run(state, queries, CcdQueryType::kVertexFace);
}
void BM_AccdEdgeEdgeHard(benchmark::State& state) {
  static const std::vector<CcdQuery> queries = hard_set(CcdQueryType::kEdgeEdge);
  run(state, queries, CcdQueryType::kEdgeEdge);
}
void BM_AccdVertexFaceRandom(benchmark::State& state) {
  static const std::vector<CcdQuery> queries = random_set(4096);
  run(state, queries, CcdQueryType::kVertexFace);
}
void BM_AccdEdgeEdgeRandom(benchmark::State& state) {
  static const std::vector<CcdQuery> queries = random_set(4096);
  run(state, queries, CcdQueryType::kEdgeEdge);
}

BENCHMARK(BM_AccdVertexFaceHard);
BENCHMARK(BM_AccdEdgeEdgeHard);
BENCHMARK(BM_AccdVertexFaceRandom);
BENCHMARK(BM_AccdEdgeEdgeRandom);

}  // namespace

BENCHMARK_MAIN();
