// `grip inspect DATASET.h5`: the dataset's provenance, then what it holds: objects, grippers,
// candidates done, success rates by gripper and by object, D1/D2 and peak stress statistics and
// failures by kind; committed rows that do not match their checksums are reported (exit 1).
// Reads with serial HDF5; needs no MPI.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <set>
#include <string>

#include "app/cli/command_line.hpp"
#include "app/commands/commands.hpp"
#include "app/dataset_probe.hpp"
#include "io/dataset_reader.hpp"
#include "io/dataset_summary.hpp"

namespace grip::commands {

namespace {

std::string percent(std::uint64_t part, std::uint64_t whole) {
  if (whole == 0) return "-";
  char text[16];
  std::snprintf(text, sizeof text, "%.1f%%",
                100.0 * static_cast<double>(part) / static_cast<double>(whole));
  return text;
}

void print_tallies(const char* title, const std::vector<io::Tally>& tallies) {
  std::printf("\n%-28s %10s %10s %10s %8s\n", title, "candidates", "done", "success", "rate");
  for (const io::Tally& tally : tallies) {
    std::printf("  %-26s %10llu %10llu %10llu %8s\n", tally.name.c_str(),
                static_cast<unsigned long long>(tally.candidates),
                static_cast<unsigned long long>(tally.done),
                static_cast<unsigned long long>(tally.success),
                percent(tally.success, tally.done).c_str());
  }
}

void print_statistics(const char* name, const io::Statistics& s, double scale) {
  if (s.count == 0) {
    std::printf("  %-18s %8s\n", name, "-");
    return;
  }
  std::printf("  %-18s %8llu %12.4g %12.4g %12.4g %12.4g\n", name,
              static_cast<unsigned long long>(s.count), s.mean * scale, s.min * scale,
              s.median * scale, s.max * scale);
}

std::size_t damaged_candidates(const io::DatasetSummary& summary) {
  std::set<std::uint64_t> candidates;
  for (const io::DamagedRow& row : summary.damaged) candidates.insert(row.damage.candidate);
  return candidates.size();
}

// One error line per damaged row, the first few of them.
void report_damage(const std::string& dataset, const std::vector<io::DamagedRow>& damaged) {
  constexpr std::size_t kShown = 20;
  for (std::size_t i = 0; i < std::min(damaged.size(), kShown); ++i) {
    const io::DamagedRow& row = damaged[i];
    const std::string round =
        row.round > 0 ? "journal line " + std::to_string(row.round) : "no journal line names it";
    spdlog::error(
        "{}: candidate {} ({}): {} does not match the checksum written with it; the candidate is "
        "not counted as done (grip farm --resume redoes it)",
        dataset, row.damage.candidate, round, row.damage.dataset);
  }
  if (damaged.size() > kShown) {
    spdlog::error("{}: {} more damaged rows", dataset, damaged.size() - kShown);
  }
}

}  // namespace

int inspect(const std::string& dataset, bool show_job) {
  const io::DatasetReader reader(dataset);
  const io::Provenance provenance = reader.provenance();
  const io::DatasetLayout& layout = reader.layout();
  std::printf("dataset     %s (%s, format version %llu)\n", dataset.c_str(), io::kFormatName,
              static_cast<unsigned long long>(io::kFormatVersion));
  std::printf("job         %s (seed %llu, job id %s)\n", provenance.job_file.c_str(),
              static_cast<unsigned long long>(provenance.seed), reader.job_id().c_str());
  std::printf("made by     grip %s (revision %s)\n", provenance.grip_version.c_str(),
              provenance.git_revision.c_str());
  std::printf("frames      %u closing + %u validation per trajectory\n", layout.closing_frames,
              layout.validation_frames);
  if (!provenance.parameters.empty()) {
    std::printf("parameters\n");
    for (const io::Parameter& parameter : provenance.parameters) {
      std::printf("  %s = %s\n", parameter.key.c_str(), parameter.value.c_str());
    }
  }
  if (show_job) {
    std::printf("job file text\n%s", provenance.job_text.c_str());
    if (!provenance.job_text.empty() && provenance.job_text.back() != '\n') std::printf("\n");
  }

  const io::DatasetSummary summary = io::summarize(reader);
  std::printf("\nobjects     %zu\ngrippers    %zu\n", layout.objects.size(),
              layout.grippers.size());
  std::printf("candidates  %llu (%llu done, %llu pending)\n",
              static_cast<unsigned long long>(summary.candidates),
              static_cast<unsigned long long>(summary.done),
              static_cast<unsigned long long>(summary.candidates - summary.done));
  if (!summary.damaged.empty()) {
    std::printf("damaged     %zu committed candidates do not match their checksums (pending)\n",
                damaged_candidates(summary));
  }
  std::printf("success     %llu of %llu done (%s)\n",
              static_cast<unsigned long long>(summary.success),
              static_cast<unsigned long long>(summary.done),
              percent(summary.success, summary.done).c_str());
  print_tallies("by gripper", summary.by_gripper);
  print_tallies("by object", summary.by_object);

  std::printf("\n%-20s %8s %12s %12s %12s %12s\n", "successful grasps", "count", "mean", "min",
              "median", "max");
  print_statistics("D1 (mm)", summary.d1, 1e3);
  print_statistics("D2 (mm)", summary.d2, 1e3);
  if (summary.peak_object_stress.count > 0) {
    print_statistics("object peak (kPa)", summary.peak_object_stress, 1e-3);
  }
  if (summary.peak_finger_stress.count > 0) {
    print_statistics("finger peak (kPa)", summary.peak_finger_stress, 1e-3);
  }
  std::printf("done candidates\n");
  print_statistics("wall (s)", summary.wall_time, 1.0);

  std::printf("\nfailures by kind\n");
  bool any = false;
  for (std::uint8_t kind = 1; kind < io::kFailureKindCount; ++kind) {
    if (summary.failures[kind] == 0) continue;
    any = true;
    const std::string name(io::to_string(static_cast<io::FailureKind>(kind)));
    std::printf("  %-24s %10llu\n", name.c_str(),
                static_cast<unsigned long long>(summary.failures[kind]));
  }
  if (!any) std::printf("  none\n");
  if (summary.damaged.empty()) return 0;
  std::fflush(stdout);
  report_damage(dataset, summary.damaged);
  return 1;
}

void declare_inspect(cli::Command& root) {
  struct InspectArgs {
    std::string dataset;
    bool job = false;
  };
  auto args = std::make_shared<InspectArgs>();
  cli::Command inspect = root.subcommand(
      "inspect", "Print a dataset's provenance and summary (success rates, D1/D2, failures)");
  inspect.option("dataset", args->dataset, "The dataset (.h5)").required();
  inspect.flag("--job", args->job, "Also print the job file text stored in the dataset");
  inspect.on_run([args] {
    check_dataset_readable(args->dataset);
    return grip::commands::inspect(args->dataset, args->job);
  });
}

}  // namespace grip::commands
