#pragma once
// `grip bench batch`: N copies of one scene (optionally each placed with a seeded jitter) run
// one after another and as one batch on one engine (solver/batch/engines.hpp), timed both ways,
// with the batch's Newton iterations, frozen fraction and memory per environment.
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "solver/batch/engines.hpp"
#include "src/scene/scene_file.hpp"

namespace grip::bench {

struct BatchBenchmarkOptions {
  std::vector<int> envs{1, 2, 4, 8, 16, 32, 64};
  int threads = 0;  // 0: all cores
  // The engine, both ways: the batch, and each copy alone in an engine of its own.
  solver::EngineDevice device = solver::EngineDevice::kCpu;
  // Seed of the per-environment jitter: each free body (affine or FEM without pins) moves by
  // up to a quarter of d_hat along each axis, so the copies' contacts and iterations differ.
  std::optional<std::uint64_t> jitter;
};

struct BatchBenchmarkRow {
  int envs = 0;
  int steps = 0;                 // per environment
  double sequential_s = 0.0;     // wall time, one environment after another, one thread each
  double batched_s = 0.0;        // wall time as one batch on the given threads
  double speedup = 0.0;          // sequential / batched
  long newton_iterations = 0;    // over all environments and steps (the same both ways)
  double frozen_fraction = 0.0;  // environment-rounds spent frozen / all environment-rounds
  double memory_mib = 0.0;       // peak resident memory of the batched run (the shared model and
                                 // every environment) above what the process held before it
  double memory_per_env_mib = 0.0;
  // (memory_mib - the 1-environment row's) / (envs - 1): what each environment after the first
  // adds; NaN without a 1-environment row or for it.
  double memory_per_added_env_mib = 0.0;
  int failed = 0;         // environments that failed (their reasons are logged)
  bool identical = true;  // batched final states equal the sequential ones bit for bit
};

struct BatchBenchmarkResult {
  std::string scene;
  int threads = 0;
  solver::EngineDevice device = solver::EngineDevice::kCpu;
  std::vector<BatchBenchmarkRow> rows;
};

// Runs the benchmark, printing a table row to `out` as each N finishes.
BatchBenchmarkResult run_batch_benchmark(const scene::SceneFile& scene, const std::string& name,
                                         const BatchBenchmarkOptions& options, std::ostream& out);

// The result as one JSON object on one line.
void write_json_line(std::ostream& out, const BatchBenchmarkResult& result);

}  // namespace grip::bench
