#include "bench/scale/scale_benchmark.hpp"

#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "bench/common/subprocess.hpp"
#include "bench/scale/commit_fit.hpp"
#include "bench/scale/trial_costs.hpp"

namespace grip::bench {
namespace {

namespace fs = std::filesystem;

struct Scenario {
  std::string name;
  ModelOptions options;
  int batch = 0;
  int round_batches = 0;
};

int positive(const std::string& what, const std::string& text) {
  try {
    std::size_t used = 0;
    const int value = std::stoi(text, &used);
    if (used == text.size() && value > 0) return value;
  } catch (const std::exception&) {
  }
  throw std::invalid_argument("--what-if " + what + ": '" + text + "' is not a positive count");
}

std::vector<Scenario> scenarios(const ScaleOptions& o) {
  std::vector<Scenario> out = {{"farm", {}, o.batch, o.round_batches}};
  for (const std::string& w : o.what_if) {
    Scenario s{w, {}, o.batch, o.round_batches};
    std::stringstream parts(w);
    std::string part;
    while (std::getline(parts, part, '+')) {  // changes combine: barrier-free+batch=1
      const std::size_t eq = part.find('=');
      const std::string key = part.substr(0, eq);
      const std::string value = eq == std::string::npos ? "" : part.substr(eq + 1);
      if (part == "heaviest-first") {
        s.options.order = UnitOrder::kHeaviestFirst;
      } else if (part == "rounds") {
        s.options.rounds = true;
      } else if (key == "round-batches" && eq != std::string::npos) {
        s.options.rounds = true;
        s.round_batches = positive(key, value);
      } else if (key == "batch" && eq != std::string::npos) {
        s.batch = positive(key, value);
      } else {
        throw std::invalid_argument("--what-if: '" + part +
                                    "' is not one of rounds, heaviest-first, "
                                    "round-batches=N, batch=N (joined by '+')");
      }
    }
    out.push_back(s);
  }
  return out;
}

double json_number(const nlohmann::json& json, const char* key, const fs::path& file) {
  const auto at = json.find(key);
  if (at == json.end() || !at->is_number()) {
    throw std::runtime_error(file.string() + ": no number '" + key + "'");
  }
  return at->get<double>();
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void run_logged(const std::vector<std::string>& args, const fs::path& log,
                const std::string& what) {
  if (run_process(args, log) != 0) {
    throw std::runtime_error("grip bench scale: " + what + " failed; see " + log.string());
  }
}

// Each rank count's probe three times, interleaved; per row size the least of the three
// medians (another user's burst of disk writes can stall every commit of one probe).
std::vector<ProbeResult> measure(const ScaleOptions& o) {
  constexpr int kRepeats = 3;
  std::vector<ProbeResult> probes(o.measure.size());
  for (int repeat = 0; repeat < kRepeats; ++repeat) {
    for (std::size_t k = 0; k < o.measure.size(); ++k) {
      const std::string ranks = std::to_string(o.measure[k]);
      const fs::path json = o.out / ("probe_" + ranks + "_" + std::to_string(repeat) + ".json");
      const fs::path log = o.out / ("probe_" + ranks + "_" + std::to_string(repeat) + ".log");
      run_logged({o.mpiexec.string(), "-np", ranks, "--oversubscribe", "--bind-to", "none",
                  o.grip.string(), "bench", "scale-probe", "--out", json.string(), "--folder",
                  o.out.string()},
                 log, "the commit probe on " + ranks + " rank(s)");
      const ProbeResult probe = read_probe_json(json);
      spdlog::info(
          "probe on {} rank(s): claim {:.2f} us, unit commits {:.2f} ms ({:.1f} kB), "
          "{:.2f} ms ({:.0f} kB), journal line {:.2f} ms; round commits {:.1f} ms ({:.0f} kB), "
          "{:.1f} ms ({:.0f} kB)",
          ranks, 1e6 * probe.claim_seconds, 1e3 * probe.unit_commits[0].seconds,
          1e-3 * probe.unit_commits[0].bytes, 1e3 * probe.unit_commits[1].seconds,
          1e-3 * probe.unit_commits[1].bytes, 1e3 * probe.journal_seconds,
          1e3 * probe.commits[0].seconds, 1e-3 * probe.commits[0].bytes,
          1e3 * probe.commits[1].seconds, 1e-3 * probe.commits[1].bytes);
      ProbeResult& best = probes[k];
      if (repeat == 0) {
        best = probe;
        continue;
      }
      best.claim_seconds = std::min(best.claim_seconds, probe.claim_seconds);
      best.claim_service = std::min(best.claim_service, probe.claim_service);
      for (std::size_t c = 0; c < best.commits.size(); ++c) {
        best.commits[c].seconds = std::min(best.commits[c].seconds, probe.commits[c].seconds);
      }
      for (std::size_t c = 0; c < best.unit_commits.size(); ++c) {
        best.unit_commits[c].seconds =
            std::min(best.unit_commits[c].seconds, probe.unit_commits[c].seconds);
      }
      best.journal_seconds = std::min(best.journal_seconds, probe.journal_seconds);
    }
  }
  return probes;
}

void apply_probes(const std::vector<ProbeResult>& probes, FarmCosts& costs) {
  if (probes.empty()) return;
  std::vector<CommitPoint> points;
  for (const ProbeResult& p : probes) {
    for (const CommitSample& c : p.commits) points.push_back({p.ranks, c.bytes, c.seconds});
  }
  costs.commit = fit_commit_model(points);
  std::vector<CommitPoint> unit_points;
  for (const ProbeResult& p : probes) {
    for (const CommitSample& c : p.unit_commits) unit_points.push_back({1, c.bytes, c.seconds});
  }
  costs.unit_commit = fit_unit_commit_model(unit_points);
  costs.journal_line = probes.back().journal_seconds;
  costs.claim.latency = probes.back().claim_seconds;
  costs.claim.service = probes.back().claim_service;
}

struct MeasuredRun {
  int ranks = 0;
  double whole = 0, plan = 0, trials = 0;
  int batch = 0;
  DatasetJob dataset;
};

MeasuredRun farm_run(const ScaleOptions& o, int ranks) {
  const std::string name = "validate_" + std::to_string(ranks);
  const fs::path dataset = o.out / (name + ".h5"), report = o.out / (name + ".json"),
                 log = o.out / (name + ".log");
  fs::remove(dataset);
  fs::remove(dataset.string() + ".journal");
  const auto start = std::chrono::steady_clock::now();
  run_logged({o.mpiexec.string(), "-np", std::to_string(ranks), "--oversubscribe", "--bind-to",
              "none", o.grip.string(), "farm", o.validate_job.string(), "--threads", "1",
              "--output", dataset.string(), "--report", report.string(), "--quiet"},
             log, "the farm run on " + std::to_string(ranks) + " rank(s)");
  MeasuredRun run;
  run.ranks = ranks;
  run.whole = seconds_since(start);
  std::ifstream in(report);
  const nlohmann::json json = nlohmann::json::parse(in, nullptr, false);
  run.plan = json_number(json, "plan_seconds", report);
  run.trials = json_number(json, "trial_seconds", report);
  run.batch = static_cast<int>(json_number(json, "batch", report));
  run.dataset = read_dataset_job(dataset);
  fs::remove(dataset);
  fs::remove(dataset.string() + ".journal");
  spdlog::info("{} on {} rank(s): {:.2f} s (planning {:.2f} s, trials {:.2f} s)",
               o.validate_job.string(), ranks, run.whole, run.plan, run.trials);
  return run;
}

// The 1-rank run's start-up (what the farm's report leaves out of the mpirun) and planning
// (spread over its objects, soft ones alike: one run cannot tell them apart).
void apply_one_rank_run(const MeasuredRun& one, FarmCosts& costs) {
  costs.startup = std::max(0.0, one.whole - one.plan - one.trials);
  costs.synthesis = 0;
  costs.prepare_rigid = costs.prepare_soft =
      one.plan / static_cast<double>(one.dataset.job.object_soft.size());
}

std::vector<ValidationRow> validate(const ScaleOptions& o, FarmCosts& costs) {
  std::vector<MeasuredRun> runs;
  for (const int ranks : o.validate_ranks) runs.push_back(farm_run(o, ranks));
  const auto one =
      std::find_if(runs.begin(), runs.end(), [](const auto& r) { return r.ranks == 1; });
  if (one == runs.end()) throw std::invalid_argument("--validate-ranks must include 1");
  apply_one_rank_run(*one, costs);
  std::vector<ValidationRow> rows;
  for (const MeasuredRun& run : runs) {
    ModelJob own = run.dataset.job, first = one->dataset.job;
    own.work_unit_size = first.work_unit_size = run.batch;
    FarmCosts c = costs;
    c.bytes_per_candidate = static_cast<double>(run.dataset.file_bytes) /
                            static_cast<double>(own.candidate_seconds.size());
    ValidationRow row;
    row.ranks = run.ranks;
    row.trials = own.candidate_seconds.size();
    row.measured = run.whole;
    row.measured_farm = run.plan + run.trials;
    row.predicted_replay = simulate_farm(own, c, run.ranks).total;
    row.predicted_one = simulate_farm(first, c, run.ranks).total;
    rows.push_back(row);
  }
  return rows;
}

std::string percent(double predicted, double measured) {
  char text[32];
  std::snprintf(text, sizeof text, "%+.1f %%", 100.0 * (predicted - measured) / measured);
  return text;
}

void write_files(const ScaleOptions& o, const ScaleResult& r) {
  std::ofstream csv(o.out / "scale.csv");
  csv << "scenario,ranks,total_s,startup_s,plan_s,trial_phase_s,efficiency,trials_per_second,"
         "work_share,claim_share,idle_share,commit_share,rounds,units\n";
  for (const ScaleRow& row : r.rows) {
    const ModelRun& m = row.run;
    const double rank_seconds = m.trial_phase * m.ranks;
    csv << row.scenario << ',' << m.ranks << ',' << m.total << ',' << m.startup << ',' << m.plan
        << ',' << m.trial_phase << ',' << row.efficiency << ','
        << static_cast<double>(r.trials) / m.total << ',' << m.work / rank_seconds << ','
        << m.claiming / rank_seconds << ',' << m.idle / rank_seconds << ','
        << m.committing / rank_seconds << ',' << m.rounds << ',' << m.units << '\n';
  }
  std::ofstream val(o.out / "validation.csv");
  val << "ranks,trials,measured_s,measured_farm_s,predicted_replay_s,predicted_one_rank_s\n";
  for (const ValidationRow& v : r.validation) {
    val << v.ranks << ',' << v.trials << ',' << v.measured << ',' << v.measured_farm << ','
        << v.predicted_replay << ',' << v.predicted_one << '\n';
  }

  const FarmCosts& c = r.costs;
  std::ofstream md(o.out / "scale.md");
  char line[512];
  md << "Costs: `" << o.costs_file.string() << "`; job: " << o.objects << " objects ("
     << o.soft_fraction * 100 << " % soft), " << o.candidates << " candidates, gripper(s)";
  for (const std::string& g : o.grippers) md << ' ' << g;
  md << "; batch " << o.batch << ", one core per rank; the rounds what-if: " << o.round_batches
     << " batches per rank per round.\n\n";
  std::snprintf(line, sizeof line,
                "Model constants: a unit's commit %.3g s + bytes / %.3g MB/s, a journal line %.3g "
                "s on rank 0; a round's commit (rounds what-if) %.3g s + %.3g s x log2(P) + bytes "
                "/ %.3g MB/s; claim %.3g us round trip, %.3g us at rank 0's counter; start-up "
                "%.3g s; planning %.3g s per rigid object, %.3g s per soft one, %.3g s per "
                "candidate; %.0f bytes per candidate; scene build %.3g s.\n\n",
                c.unit_commit.latency,
                c.unit_commit.bandwidth > 0 ? c.unit_commit.bandwidth * 1e-6 : INFINITY,
                c.journal_line, c.commit.latency, c.commit.per_log2,
                c.commit.bandwidth > 0 ? c.commit.bandwidth * 1e-6 : INFINITY,
                c.claim.latency * 1e6, c.claim.service * 1e6, c.startup, c.prepare_rigid,
                c.prepare_soft, c.synthesis, c.bytes_per_candidate, c.scene_build);
  md << line;
  if (!r.validation.empty()) {
    md << "Validation: `" << o.validate_job.string()
       << "` under mpirun, one thread per rank.\n\n"
          "| ranks | trials | measured (s) | predicted, own costs (s) | error | predicted, 1-rank "
          "costs (s) | error |\n| --- | --- | --- | --- | --- | --- | --- |\n";
    for (const ValidationRow& v : r.validation) {
      std::snprintf(line, sizeof line, "| %d | %llu | %.2f | %.2f | %s | %.2f | %s |\n", v.ranks,
                    static_cast<unsigned long long>(v.trials), v.measured, v.predicted_replay,
                    percent(v.predicted_replay, v.measured).c_str(), v.predicted_one,
                    percent(v.predicted_one, v.measured).c_str());
      md << line;
    }
    md << '\n';
  }
  std::snprintf(line, sizeof line, "Prediction, %llu trials (1 rank: %.0f s):\n\n",
                static_cast<unsigned long long>(r.trials), r.one_rank_seconds);
  md << line
     << "| scenario | ranks | time to solution (s) | trial phase (s) | efficiency | trials | "
        "claims | idle | commits | rounds |\n"
        "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for (const ScaleRow& row : r.rows) {
    const ModelRun& m = row.run;
    const double rank_seconds = m.trial_phase * m.ranks;
    std::snprintf(line, sizeof line,
                  "| %s | %d | %.1f | %.1f | %.1f %% | %.1f %% | %.2f %% | %.1f %% | %.2f %% | "
                  "%llu |\n",
                  row.scenario.c_str(), m.ranks, m.total, m.trial_phase, 100 * row.efficiency,
                  100 * m.work / rank_seconds, 100 * m.claiming / rank_seconds,
                  100 * m.idle / rank_seconds, 100 * m.committing / rank_seconds,
                  static_cast<unsigned long long>(m.rounds));
    md << line;
  }
}

}  // namespace

ScaleResult run_scale(const ScaleOptions& options) {
  if (options.ranks.empty() || options.batch < 1 || options.round_batches < 1 ||
      options.soft_fraction < 0 || options.soft_fraction > 1) {
    throw std::invalid_argument(
        "grip bench scale: give rank counts, a batch and round size >= 1 and a soft fraction "
        "in [0, 1]");
  }
  const std::vector<Scenario> cases = scenarios(options);
  fs::create_directories(options.out);
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);

  ScaleResult result;
  result.costs = options.costs;
  result.probes = measure(options);
  apply_probes(result.probes, result.costs);
  if (!options.validate_job.empty()) result.validation = validate(options, result.costs);

  const CostSamples samples = read_cost_samples(options.costs_file);
  ModelJob job = sampled_job(samples, options.grippers, options.objects, options.candidates,
                             options.soft_fraction, options.seed);
  result.trials = job.candidate_seconds.size();
  job.work_unit_size = options.batch;
  job.round_work_units = options.round_batches;
  result.one_rank_seconds = simulate_farm(job, result.costs, 1).total;
  for (const Scenario& s : cases) {
    ModelJob scenario_job = job;
    scenario_job.work_unit_size = s.batch;
    scenario_job.round_work_units = s.round_batches;
    for (const int ranks : options.ranks) {
      ScaleRow row;
      row.scenario = s.name;
      row.run = simulate_farm(scenario_job, result.costs, ranks, s.options);
      row.efficiency = result.one_rank_seconds / (ranks * row.run.total);
      result.rows.push_back(row);
    }
  }
  write_files(options, result);
  plot("bench/scale/plot_scale.py",
       {(options.out / "scale.csv").string(), (options.out / "scale.png").string()}, options.out);
  return result;
}

}  // namespace grip::bench
