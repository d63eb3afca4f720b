#include "bench/batch/batch_benchmark.hpp"

#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <random>
#include <utility>

#include "solver/batch/engines.hpp"
#include "src/json/json_text.hpp"
#include "src/platform/process_memory.hpp"

namespace grip::bench {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Where each copy starts: the scene's placement moved by a seeded jitter of its free bodies.
void place_copy(solver::EnvironmentHandle& env, int copy, const BatchBenchmarkOptions& options) {
  if (!options.jitter) return;
  const solver::Model& model = env.model();
  std::mt19937_64 rng(*options.jitter * 1000003ull + static_cast<std::uint64_t>(copy));
  std::uniform_real_distribution<double> uniform(-0.25, 0.25);
  std::vector<char> pinned(model.bodies().size(), 0);
  for (const solver::PinnedVertex& pin : model.pins()) pinned[pin.body] = 1;
  for (std::size_t b = 0; b < model.bodies().size(); ++b) {
    if (!model.bodies()[b].has_dofs() || pinned[b]) continue;
    const Eigen::Vector3d shift(uniform(rng), uniform(rng), uniform(rng));
    env.place(static_cast<int>(b),
              Eigen::Isometry3d(Eigen::Translation3d(model.sim().d_hat * shift)));
  }
}

}  // namespace

BatchBenchmarkResult run_batch_benchmark(const scene::SceneFile& scene, const std::string& name,
                                         const BatchBenchmarkOptions& options, std::ostream& out) {
  const int steps = static_cast<int>(std::llround(scene.duration / scene.scene.sim.dt));
  BatchBenchmarkResult result;
  result.scene = name;
  result.threads = solver::make_engine(options.device, options.threads)->threads();
  result.device = options.device;
  out << "scene " << name << ", " << steps << " steps per environment, " << result.threads
      << " thread(s), engine " << solver::device_name(options.device)
      << (options.jitter ? ", jittered starts" : "") << "\n"
      << "  envs  sequential s  batched s  speedup  Newton its  frozen  MiB/env  MiB/added  "
         "identical\n";
  for (const int n : options.envs) {
    BatchBenchmarkRow row;
    row.envs = n;
    row.steps = steps;

    // Batched first, on a trimmed heap, so that its memory is measured from a clean baseline:
    // the model (shared by all copies) and every environment's own state.
    const platform::MemoryPeak memory;
    const std::shared_ptr<const solver::Model> model = solver::Model::build(scene.scene);
    std::vector<Eigen::VectorXd> batched_state;
    {
      const Clock::time_point start = Clock::now();
      const std::unique_ptr<solver::Engine> batch =
          solver::make_engine(options.device, options.threads);
      for (int e = 0; e < n; ++e) place_copy(batch->environment(batch->add(model)), e, options);
      long iterations = 0;
      long frozen = 0;
      for (int s = 0; s < steps && batch->any_active(); ++s) {
        const solver::BatchStepReport report = batch->step();
        iterations += report.iterations;
        frozen += report.frozen;
      }
      row.batched_s = seconds_since(start);
      row.memory_mib = memory.mib();
      row.frozen_fraction =
          iterations + frozen > 0 ? static_cast<double>(frozen) / (iterations + frozen) : 0.0;
      for (int e = 0; e < n; ++e) {
        const solver::EnvironmentHandle& env = batch->environment(e);
        row.newton_iterations += env.statistics().newton_iterations;
        if (env.failed()) {
          ++row.failed;
          spdlog::warn("environment {} of {}: {}", e, n, env.failure());
        }
        batched_state.push_back(env.dofs());
      }
    }
    row.memory_per_env_mib = row.memory_mib / n;
    row.memory_per_added_env_mib = std::numeric_limits<double>::quiet_NaN();
    for (const BatchBenchmarkRow& first : result.rows) {
      if (first.envs == 1 && n > 1) {
        row.memory_per_added_env_mib = (row.memory_mib - first.memory_mib) / (n - 1);
      }
    }

    // The same copies one after another, each alone.
    const Clock::time_point start = Clock::now();
    long sequential_iterations = 0;
    for (int e = 0; e < n; ++e) {
      const std::unique_ptr<solver::Engine> alone = solver::make_engine(options.device, 1);
      solver::EnvironmentHandle& env = alone->environment(alone->add(model));
      place_copy(env, e, options);
      for (int s = 0; s < steps && alone->any_active(); ++s) alone->step();
      sequential_iterations += env.statistics().newton_iterations;
      row.identical = row.identical && env.dofs() == batched_state[e];
    }
    row.sequential_s = seconds_since(start);
    row.identical = row.identical && sequential_iterations == row.newton_iterations;
    row.speedup = row.sequential_s / row.batched_s;

    out << std::fixed << std::setw(6) << n << std::setw(14) << std::setprecision(3)
        << row.sequential_s << std::setw(11) << row.batched_s << std::setw(9)
        << std::setprecision(2) << row.speedup << std::setw(12) << row.newton_iterations
        << std::setw(8) << std::setprecision(3) << row.frozen_fraction << std::setw(9)
        << std::setprecision(2) << row.memory_per_env_mib << std::setw(11)
        << row.memory_per_added_env_mib << std::setw(11) << (row.identical ? "yes" : "NO")
        << (row.failed ? "  (failures)" : "") << "\n"
        << std::defaultfloat << std::flush;
    result.rows.push_back(row);
  }
  return result;
}

void write_json_line(std::ostream& out, const BatchBenchmarkResult& result) {
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (const BatchBenchmarkRow& r : result.rows) {
    rows.push_back(nlohmann::ordered_json{{"envs", r.envs},
                                          {"steps", r.steps},
                                          {"sequential_s", r.sequential_s},
                                          {"batched_s", r.batched_s},
                                          {"speedup", r.speedup},
                                          {"newton_iterations", r.newton_iterations},
                                          {"frozen_fraction", r.frozen_fraction},
                                          {"memory_mib", r.memory_mib},
                                          {"memory_per_env_mib", r.memory_per_env_mib},
                                          {"memory_per_added_env_mib", r.memory_per_added_env_mib},
                                          {"failed", r.failed},
                                          {"identical", r.identical}});
  }
  const nlohmann::ordered_json line = {{"benchmark", "batch"},
                                       {"scene", result.scene},
                                       {"threads", result.threads},
                                       {"device", solver::device_name(result.device)},
                                       {"rows", std::move(rows)}};
  out << json::text(line, "%.6g") << '\n';
}

}  // namespace grip::bench
