// grip farm JOB.toml: the dataset farm, under mpirun or as one process (docs/farm.md). Rank 0
// reports progress and, at the end, where the dataset is and its summary.
#include <mpi.h>
#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/cli/command_line.hpp"
#include "app/cli/version.hpp"
#include "app/commands/commands.hpp"
#include "app/dataset_probe.hpp"
#include "farm/farm.hpp"
#include "io/dataset_error.hpp"
#include "src/config/config.hpp"
#include "src/json/json_text.hpp"

namespace grip::commands {
namespace {

struct FarmArgs {
  std::string job;     // job file (docs/job-format.md)
  std::string output;  // the dataset; empty: the job's [job] output
  bool resume = false;
  int threads = 0;     // per rank; 0: the node's cores shared by its ranks
  int batch = 0;       // candidates per work unit; 0: the job's [farm] batch, else 4 per thread
  std::string report;  // JSON summary of the run (rank 0); none when empty
  std::vector<std::string> petsc_options;  // after a lone `--`: the job's PETSc groups'
};

// MPI for the command's lifetime; a plain `grip farm` (no mpirun) runs as one rank.
class MpiSession {
 public:
  MpiSession() {
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  }
  ~MpiSession() { MPI_Finalize(); }
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
};

void write_report(const std::string& file, const farm::FarmReport& r) {
  std::ofstream out(file);
  if (!out) throw std::runtime_error("--report " + file + ": cannot write the file");
  const nlohmann::ordered_json report = {{"dataset", r.dataset.string()},
                                         {"ranks", r.ranks},
                                         {"threads", r.threads},
                                         {"batch", r.work_unit_size},
                                         {"candidates", r.candidates},
                                         {"done_before", r.done_before},
                                         {"done", r.done},
                                         {"plan_seconds", r.plan_seconds},
                                         {"trial_seconds", r.trial_seconds},
                                         {"interrupted", r.interrupted},
                                         {"petsc_groups", r.petsc_groups},
                                         {"petsc_solves", r.petsc_solves}};
  out << json::text(report, "%.6f") << '\n';
}

// GRIP_PROGRESS_INTERVAL: seconds between progress lines (docs/farm.md); -1 when unset, none
// when it is not a number >= 0.
std::optional<double> progress_interval() {
  const char* text = std::getenv("GRIP_PROGRESS_INTERVAL");
  if (text == nullptr || *text == '\0') return -1.0;
  char* end = nullptr;
  const double seconds = std::strtod(text, &end);
  if (*end != '\0' || !std::isfinite(seconds) || seconds < 0) return std::nullopt;
  return seconds;
}

int farm(const FarmArgs& args) {
  const std::optional<double> interval = progress_interval();
  if (!interval) {
    std::fprintf(stderr,
                 "grip: GRIP_PROGRESS_INTERVAL: must be a number of seconds >= 0, not '%s'\n",
                 std::getenv("GRIP_PROGRESS_INTERVAL"));
    return 2;
  }
  const MpiSession mpi;
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  if (rank != 0) spdlog::set_level(spdlog::level::warn);  // rank 0 speaks for the run

  farm::FarmOptions options;
  options.job = args.job;
  options.output = args.output;
  options.resume = args.resume;
  options.threads = args.threads;
  options.work_unit_size = args.batch;
  options.progress_interval = *interval;
  options.grip_version = version();
  options.git_revision = git_revision();
  options.check_dataset = check_dataset_readable;
  options.petsc_options = args.petsc_options;
  farm::FarmReport report;
  try {
    report = farm::run_farm(options, MPI_COMM_WORLD);
  } catch (const config::ConfigError& e) {
    // Every rank read the same job and fails alike: one message, a clean exit.
    if (rank == 0) spdlog::error("{}", e.what());
    return 1;
  } catch (const io::DatasetError& e) {
    if (rank == 0) spdlog::error("{}", e.what());
    return 1;
  } catch (const farm::TrialError& e) {  // shared by every rank after the round's commit
    if (rank == 0) spdlog::error("{}", e.what());
    return 1;
  } catch (const std::exception& e) {
    // A failure on one rank would leave the others waiting in a collective: stop them all.
    // Committed rounds are safe; --resume continues from them.
    spdlog::error("rank {}: {}", rank, e.what());
    if (ranks > 1) MPI_Abort(MPI_COMM_WORLD, 1);
    return 1;
  }

  if (rank == 0) {
    std::printf(
        "\ndataset %s: %llu of %llu candidates done (%llu by this run, %d rank(s) x %d "
        "thread(s), batches of %d); planning %.1f s, trials %.1f s\n",
        report.dataset.c_str(), static_cast<unsigned long long>(report.done_before + report.done),
        static_cast<unsigned long long>(report.candidates),
        static_cast<unsigned long long>(report.done), report.ranks, report.threads,
        report.work_unit_size, report.plan_seconds, report.trial_seconds);
    if (!args.report.empty()) write_report(args.report, report);
    if (report.interrupted) {
      std::printf("stopped early: continue with  grip farm %s --resume\n", args.job.c_str());
    } else {
      std::printf("\n");
      inspect(report.dataset.string(), false);
    }
    std::fflush(stdout);
  }
  return report.interrupted ? 130 : 0;
}

}  // namespace

void declare_farm(cli::Command& root) {
  auto args = std::make_shared<FarmArgs>();
  cli::Command farm = root.subcommand(
      "farm", "Generate a dataset from a job file, as one process or under mpirun (docs/farm.md)");
  farm.option("job", args->job, "Job file (docs/job-format.md)").required();
  farm.option("--output", args->output, "The dataset (default: the job's [job] output)")
      .check(cli::Check::output_file());
  farm.flag("--resume", args->resume, "Continue an interrupted dataset of the same job");
  farm.option("--threads", args->threads,
              "Threads per rank (default: this node's cores shared by its ranks)")
      .check(cli::Check::count());
  farm.option("--batch", args->batch,
              "Candidates per batch (default: the job's, else 4 per thread)")
      .check(cli::Check::count());
  farm.option("--report", args->report, "Write a JSON summary of the run here")
      .check(cli::Check::output_file());
  farm.takes_petsc_options(args->petsc_options);  // the job's PETSc groups
  farm.on_run([args] { return grip::commands::farm(*args); });
}

}  // namespace grip::commands
