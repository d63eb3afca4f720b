// grip bench scale: the farm simulated at thousands of ranks from costs measured here, and
// grip bench scale-probe, its claim and commit probe under mpirun
// (bench/scale/scale_benchmark.hpp, docs/farm.md).
#include <mpi.h>
#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <utility>

#include "bench/scale/commit_probe.hpp"
#include "bench/scale/scale_benchmark.hpp"
#include "src/app/commands.hpp"
#include "src/json/json_text.hpp"

namespace grip::commands {

int bench_scale(const BenchScaleArgs& args) {
  bench::ScaleOptions options;
  options.costs_file = args.costs;
  options.grippers = args.grippers;
  options.objects = args.objects;
  options.candidates = args.candidates;
  options.soft_fraction = args.soft_fraction;
  options.seed = args.seed;
  options.ranks = args.ranks;
  options.batch = args.batch;
  options.round_batches = args.round_batches;
  options.measure = args.measure;
  options.validate_job = args.validate;
  options.validate_ranks = args.validate_ranks;
  options.what_if = args.what_if;
  options.out = args.out;
  bench::FarmCosts& c = options.costs;
  c.commit = {args.commit_latency, args.commit_per_log2, args.commit_bandwidth};
  c.unit_commit = {args.unit_commit_latency, 0.0, args.unit_commit_bandwidth};
  c.journal_line = args.journal_line;
  c.claim = {args.claim_latency, args.claim_service};
  c.startup = args.startup;
  c.prepare_rigid = args.prepare_rigid;
  c.prepare_soft = args.prepare_soft;
  c.synthesis = args.synthesis;
  c.scene_build = args.scene_build;
  c.bytes_per_candidate = args.bytes_per_candidate;
  c.broadcast_per_log2 = args.broadcast_per_log2;
  options.grip = std::filesystem::read_symlink("/proc/self/exe");
  options.mpiexec = GRIP_MPIEXEC;
  bench::ScaleResult result;
  try {
    result = bench::run_scale(options);
  } catch (const std::invalid_argument& e) {
    spdlog::error("grip bench scale: {}", e.what());
    return 2;
  }

  for (const bench::ValidationRow& v : result.validation) {
    std::printf(
        "validation, %d rank(s): measured %.2f s, predicted %.2f s (%+.1f %%), from the "
        "1-rank costs %.2f s (%+.1f %%)\n",
        v.ranks, v.measured, v.predicted_replay,
        100 * (v.predicted_replay - v.measured) / v.measured, v.predicted_one,
        100 * (v.predicted_one - v.measured) / v.measured);
  }
  std::printf("%-28s %6s %12s %12s %10s\n", "scenario", "ranks", "total (s)", "trials (s)",
              "efficiency");
  for (const bench::ScaleRow& r : result.rows) {
    std::printf("%-28s %6d %12.1f %12.1f %9.1f%%\n", r.scenario.c_str(), r.run.ranks, r.run.total,
                r.run.trial_phase, 100 * r.efficiency);
  }
  const std::filesystem::path out = args.out;
  std::printf("table: %s, %s%s\n", (out / "scale.md").c_str(), (out / "scale.csv").c_str(),
              std::filesystem::exists(out / "scale.png") ? ", plot: scale.png" : "");
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (const bench::ScaleRow& r : result.rows) {
    rows.push_back({{"scenario", r.scenario},
                    {"ranks", r.run.ranks},
                    {"total_seconds", r.run.total},
                    {"efficiency", r.efficiency}});
  }
  nlohmann::ordered_json validation = nlohmann::ordered_json::array();
  for (const bench::ValidationRow& v : result.validation) {
    validation.push_back({{"ranks", v.ranks},
                          {"measured_seconds", v.measured},
                          {"predicted_seconds", v.predicted_replay},
                          {"predicted_from_one_rank_seconds", v.predicted_one}});
  }
  const nlohmann::ordered_json summary = {{"trials", result.trials},
                                          {"one_rank_seconds", result.one_rank_seconds},
                                          {"validation", std::move(validation)},
                                          {"rows", std::move(rows)}};
  std::printf("%s\n", json::text(summary, "%.4f").c_str());
  return 0;
}

int bench_scale_probe(const BenchScaleProbeArgs& args) {
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const bench::ProbeResult result = bench::probe_commit_costs(MPI_COMM_WORLD, args.folder);
  if (rank == 0) bench::write_probe_json(args.out, result);
  MPI_Finalize();
  return 0;
}

}  // namespace grip::commands
