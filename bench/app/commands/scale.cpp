// grip bench scale: the farm simulated at thousands of ranks from costs measured here, and
// grip bench scale-probe, its claim and commit probe under mpirun
// (bench/scale/scale_benchmark.hpp, docs/farm.md).
#include <mpi.h>
#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <utility>

#include "app/cli/command_line.hpp"
#include "bench/app/commands.hpp"
#include "bench/scale/commit_probe.hpp"
#include "bench/scale/scale_benchmark.hpp"
#include "src/json/json_text.hpp"

namespace grip::commands {
namespace {

// grip bench scale [--costs FILE] [--ranks 64,...] [--measure 1,2,3] [--validate JOB]
// [--what-if ...] [--out DIR]: the farm's protocol simulated from measured costs to thousands
// of ranks, checked against real runs (bench/scale/, docs/farm.md).
struct BenchScaleArgs {
  std::string costs = "docs/results/trial/trial.csv";  // grip bench trial's trial.csv or a dataset
  std::vector<std::string> grippers{"fin-ray"};
  std::uint64_t objects = 1200;
  std::uint64_t candidates = 100000;
  double soft_fraction = 0.5;
  std::uint64_t seed = 1;
  std::vector<int> ranks{64, 128, 256, 512, 1024, 2048, 4096};
  int batch = 4;
  int round_batches = 4;     // the rounds what-if's work units per rank per round
  std::vector<int> measure;  // rank counts for the commit probe; empty: the constants
  std::string validate;      // a job run at validate_ranks and compared
  std::vector<int> validate_ranks{1, 2, 3};
  std::vector<std::string> what_if;  // rounds, heaviest-first, round-batches=N, batch=N
  // The model's constants where no measurement replaces them (docs/farm.md gives their source).
  double unit_commit_latency = 0.00174;
  double unit_commit_bandwidth = 443e6;
  double journal_line = 0.000366;
  double commit_latency = 0.0348;
  double commit_per_log2 = 0.00263;
  double commit_bandwidth = 340e6;
  double claim_latency = 2.59e-6;
  double claim_service = 0.864e-6;
  double startup = 0.794;
  double prepare_rigid = 0.0501;
  double prepare_soft = 0.0501;
  double synthesis = 0.0;
  double scene_build = 0.0;
  double bytes_per_candidate = 400;
  double broadcast_per_log2 = 5e-6;
  std::string out = "out/bench-scale";
};
// grip bench scale-probe --out FILE --folder DIR, under mpirun: the claim and commit costs
// grip bench scale --measure fits its model to (bench/scale/commit_probe.hpp).
struct BenchScaleProbeArgs {
  std::string out;
  std::string folder;
};

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
  options.grip = cli::sibling_program("grip");
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

// The model's constants where no measurement replaces them (docs/farm.md gives their source).
void declare_model_constants(cli::Command& scale, BenchScaleArgs& args) {
  const auto seconds = [&](const char* name, double& value, const char* what) {
    scale.option(name, value, what).show_default().check(cli::Check::non_negative());
  };
  seconds("--unit-commit-latency", args.unit_commit_latency,
          "s per work unit's commit (without --measure)");
  seconds("--unit-commit-bandwidth", args.unit_commit_bandwidth,
          "bytes/s into the file of work units' commits, 0: unlimited (without --measure)");
  seconds("--journal-line", args.journal_line,
          "s of rank 0's time per journal line (without --measure)");
  seconds("--commit-latency", args.commit_latency,
          "s per round's commit, rounds what-if (without --measure)");
  seconds("--commit-per-log2", args.commit_per_log2,
          "s per round's commit per log2(ranks) (without --measure)");
  seconds("--commit-bandwidth", args.commit_bandwidth,
          "bytes/s of round commits, 0: unlimited (without --measure)");
  seconds("--claim-latency", args.claim_latency, "s, a claim's round trip");
  seconds("--claim-service", args.claim_service, "s a claim holds rank 0's counter");
  seconds("--startup", args.startup, "s of start-up (without --validate)");
  seconds("--prepare-rigid", args.prepare_rigid,
          "s to prepare a rigid object (without --validate)");
  seconds("--prepare-soft", args.prepare_soft, "s to prepare a soft object (without --validate)");
  seconds("--synthesis", args.synthesis, "s per candidate synthesized");
  seconds("--scene-build", args.scene_build, "s to build a trial scene");
  seconds("--bytes-per-candidate", args.bytes_per_candidate,
          "Bytes committed per candidate of the simulated job");
  seconds("--broadcast-per-log2", args.broadcast_per_log2,
          "s per planning broadcast per log2(ranks)");
}

}  // namespace

void declare_bench_scale(cli::Command& group) {
  auto args = std::make_shared<BenchScaleArgs>();
  cli::Command scale = group.subcommand(
      "scale",
      "The farm simulated at 64 to 4,096 ranks from measured costs, checked against real runs");
  scale
      .option("--costs", args->costs,
              "Trial costs: grip bench trial's trial.csv or a finished dataset (.h5)")
      .show_default()
      .check(cli::Check::existing_file());
  scale
      .option("--grippers", args->grippers,
              "Grippers of the simulated job (classes 'GRIPPER x rigid|soft' in the costs)")
      .list()
      .show_default();
  scale.option("--objects", args->objects, "Objects of the simulated job")
      .show_default()
      .check(cli::Check::positive_count());
  scale.option("--candidates", args->candidates, "Candidates of the simulated job")
      .show_default()
      .check(cli::Check::positive_count());
  scale
      .option("--soft-fraction", args->soft_fraction,
              "Fraction of the simulated job's objects that are soft")
      .show_default()
      .check(cli::Check::fraction());
  scale.option("--seed", args->seed, "Seed drawing each candidate's trial cost")
      .show_default()
      .check(cli::Check::count());
  scale.option("--ranks", args->ranks, "Rank counts to predict")
      .list()
      .show_default()
      .check(cli::Check::positive_count());
  scale.option("--batch", args->batch, "Candidates per work unit")
      .show_default()
      .check(cli::Check::positive_count());
  scale
      .option("--round-batches", args->round_batches,
              "Work units per rank per round of the rounds what-if")
      .show_default()
      .check(cli::Check::positive_count());
  scale
      .option("--measure", args->measure,
              "Rank counts to measure claims and commits at under mpirun, e.g. 1,2,3")
      .list()
      .check(cli::Check::positive_count());
  scale
      .option("--validate", args->validate,
              "Job to run under mpirun and compare with the model (e.g. jobs/demo.toml)")
      .check(cli::Check::existing_file());
  scale
      .option("--validate-ranks", args->validate_ranks,
              "Rank counts of the validation runs (1 included)")
      .list()
      .show_default()
      .check(cli::Check::positive_count());
  scale
      .option("--what-if", args->what_if,
              "Scenarios beside the farm's: rounds (the former commits), heaviest-first, "
              "round-batches=N (rounds of N), batch=N")
      .list();
  declare_model_constants(scale, *args);
  scale
      .option("--out", args->out,
              "Folder for scale.md, scale.csv, validation.csv, the plot and the runs")
      .show_default()
      .check(cli::Check::output_folder());
  scale.on_run([args] { return bench_scale(*args); });
}

void declare_bench_scale_probe(cli::Command& group) {
  auto args = std::make_shared<BenchScaleProbeArgs>();
  cli::Command probe = group.subcommand(
      "scale-probe", "Under mpirun: claim and commit costs for grip bench scale --measure");
  probe.option("--out", args->out, "JSON result (rank 0)")
      .required()
      .check(cli::Check::output_file());
  probe.option("--folder", args->folder, "Folder for the scratch dataset")
      .required()
      .check(cli::Check::output_folder());
  probe.on_run([args] { return bench_scale_probe(*args); });
}

}  // namespace grip::commands
