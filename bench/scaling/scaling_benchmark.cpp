#include "bench/scaling/scaling_benchmark.hpp"

#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>

#include "bench/common/subprocess.hpp"

namespace grip::bench {
namespace {

namespace fs = std::filesystem;

double number(const nlohmann::json& report, const std::string& key) {
  const auto value = report.find(key);
  if (value == report.end() || !value->is_number()) {
    throw std::runtime_error("the farm's report lacks '" + key + "'");
  }
  return value->get<double>();
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

void write_tables(const fs::path& out, const std::vector<ScalingRow>& rows,
                  const ScalingOptions& o) {
  std::ofstream csv(out / "scaling.csv");
  csv << "ranks,threads,envs,batch,trials,trial_seconds,total_seconds,trials_per_second,speedup\n";
  std::ofstream md(out / "scaling.md");
  md << "Job `" << o.job.string() << "`, median of " << o.repeats << " runs per setting.\n\n"
     << "| ranks | threads/rank | batch | trials | trial phase (s) | whole run (s) | trials/s | "
        "speedup |\n| --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for (const ScalingRow& r : rows) {
    csv << r.ranks << ',' << r.threads << ',' << r.envs << ',' << r.batch << ',' << r.trials << ','
        << r.trial_seconds << ',' << r.total_seconds << ',' << r.trials_per_second << ','
        << r.speedup << '\n';
    char line[256];
    std::snprintf(line, sizeof line, "| %d | %d | %d | %d | %.2f | %.2f | %.3f | %.2fx |\n",
                  r.ranks, r.threads, r.batch, r.trials, r.trial_seconds, r.total_seconds,
                  r.trials_per_second, r.speedup);
    md << line;
  }
}

}  // namespace

std::vector<ScalingRow> run_scaling(const ScalingOptions& options) {
  if (options.ranks.empty() || options.envs.empty() || options.repeats < 1) {
    throw std::invalid_argument(
        "grip bench scaling: give at least one rank count, one batch size "
        "and one repeat");
  }
  fs::create_directories(options.out);
  // mpirun refuses to start as root without these; the runs inherit them.
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
  std::vector<ScalingRow> rows;
  for (int ranks : options.ranks) {
    for (int envs : options.envs) {
      ScalingRow row;
      row.ranks = ranks;
      row.envs = envs;
      rows.push_back(row);
    }
  }
  std::vector<std::vector<double>> totals(rows.size());
  for (int repeat = 0; repeat < options.repeats; ++repeat) {
    for (std::size_t k = 0; k < rows.size(); ++k) {
      ScalingRow& row = rows[k];
      const std::string name = fmt::format("r{}_e{}_{}", row.ranks, row.envs, repeat);
      const fs::path dataset = options.out / (name + ".h5"),
                     report = options.out / (name + ".json"), log = options.out / (name + ".log");
      fs::remove(dataset);
      fs::remove(dataset.string() + ".journal");
      std::vector<std::string> args = {options.mpiexec.string(),
                                       "-np",
                                       std::to_string(row.ranks),
                                       "--oversubscribe",
                                       "--bind-to",
                                       "none",
                                       options.grip.string(),
                                       "farm",
                                       options.job.string(),
                                       "--output",
                                       dataset.string(),
                                       "--report",
                                       report.string(),
                                       "--quiet"};
      if (row.envs > 0) args.insert(args.end(), {"--batch", std::to_string(row.envs)});
      if (options.threads > 0)
        args.insert(args.end(), {"--threads", std::to_string(options.threads)});
      const auto start = std::chrono::steady_clock::now();
      if (run_process(args, log) != 0) {
        throw std::runtime_error("grip bench scaling: the run with " + std::to_string(row.ranks) +
                                 " rank(s) failed; see " + log.string());
      }
      totals[k].push_back(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      std::ifstream in(report);
      const nlohmann::json farm_report = nlohmann::json::parse(in, nullptr, false);
      if (farm_report.is_discarded()) {
        throw std::runtime_error("grip bench scaling: the farm's report " + report.string() +
                                 " is not JSON");
      }
      row.batch = static_cast<int>(number(farm_report, "batch"));
      row.threads = static_cast<int>(number(farm_report, "threads"));
      row.trials = static_cast<int>(number(farm_report, "done"));
      row.runs.push_back(number(farm_report, "trial_seconds"));
      fs::remove(dataset);
      fs::remove(dataset.string() + ".journal");
      spdlog::info("{} rank(s) x {} thread(s), batch {}: {} trials in {:.2f} s (repeat {})",
                   row.ranks, row.threads, row.batch, row.trials, row.runs.back(), repeat + 1);
    }
  }
  for (std::size_t k = 0; k < rows.size(); ++k) {
    ScalingRow& row = rows[k];
    row.trial_seconds = median(row.runs);
    row.total_seconds = median(totals[k]);
    row.trials_per_second = row.trials / row.trial_seconds;
    row.speedup = row.trials_per_second / rows.front().trials_per_second;
  }
  write_tables(options.out, rows, options);

  plot("bench/scaling/plot_scaling.py",
       {(options.out / "scaling.csv").string(), (options.out / "scaling.png").string()},
       options.out);
  return rows;
}

}  // namespace grip::bench
