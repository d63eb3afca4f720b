#include "bench/cost/cost_report.hpp"

#include <spdlog/fmt/fmt.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <iomanip>

#include "bench/common/table_text.hpp"
#include "bench/robustness/robustness_report.hpp"
#include "src/json/json_text.hpp"

namespace grip::bench {
namespace fs = std::filesystem;
namespace {

// kCostStages as the tables head them.
constexpr std::array<std::string_view, kCostStages.size()> kStageHeads = {
    "broad phase", "derivatives", "assembly",     "factorization", "solve",
    "CCD",         "line search", "friction lag", "diagnostics",   "protocol"};

std::string statistics_text(const CostStatistics& s, int decimals) {
  return fixed_or_dash(s.mean, decimals) + " | " + fixed_or_dash(s.median, decimals) + " | " +
         fixed_or_dash(s.p90, decimals) + " | " + fixed_or_dash(s.max, decimals);
}

// The shapes and candidates an arm's sets asked for, in words.
std::string plan_text(const CostResult& result, const std::string& arm) {
  int categories = 0, seeds = 0, candidates = 0;
  for (const RobustnessSet& set : result.sets) {
    if (cost_arm_name(set.gripper, set.soft) != arm) continue;
    ++categories;
    seeds = set.seeds;
    candidates = set.candidates;
  }
  return fmt::format("{} categories x {} shape(s) x {} candidates", categories, seeds, candidates);
}

void write_models(std::ostream& md, const CostResult& result) {
  md << "| arm | gripper simulated as | objects simulated as | asked for |\n"
     << "| --- | --- | --- | --- |\n";
  for (const std::string& arm : result.arms) {
    const auto set = std::find_if(result.sets.begin(), result.sets.end(), [&](const auto& s) {
      return cost_arm_name(s.gripper, s.soft) == arm;
    });
    md << "| " << arm << " | " << robustness_gripper_model(set->gripper, result.production_models)
       << " | " << robustness_object_model(set->soft, result.production_models) << " | "
       << plan_text(result, arm) << " |\n";
  }
}

void write_stage_table(std::ostream& md, const CostResult& result) {
  md << "| arm | failing trials | CPU s |";
  for (const std::string_view head : kStageHeads) md << ' ' << head << " |";
  md << "\n|---|---:|---:|";
  for (std::size_t i = 0; i < kStageHeads.size(); ++i) md << "---:|";
  md << '\n';
  for (const std::string& arm : result.arms) {
    const std::vector<const CostRun*> failing = failing_runs(result, arm);
    double cpu = 0.0;
    for (const CostRun* run : failing) cpu += run->cpu_seconds;
    md << "| " << arm << " | " << failing.size() << " | " << fixed_or_dash(cpu, 3) << " |";
    for (const double share : stage_shares(failing))
      md << ' ' << fixed_or_dash(100 * share, 1) << " |";
    md << '\n';
  }
}

void write_setup_table(std::ostream& md, const CostResult& result) {
  md << "| arm | shapes | CPU s per shape: mean | median | p90 | max | total |\n"
     << "|---|---:|---:|---:|---:|---:|---:|\n";
  for (const std::string& arm : result.arms) {
    std::vector<double> setup;
    double total = 0.0;
    for (const CostShape& shape : result.shapes) {
      if (shape.arm != arm) continue;
      setup.push_back(shape.setup_cpu_seconds);
      total += shape.setup_cpu_seconds;
    }
    md << "| " << arm << " | " << setup.size() << " | "
       << statistics_text(cost_statistics(setup), 3) << " | " << fixed_or_dash(total, 3) << " |\n";
  }
}

void write_reference(std::ostream& md, const CostResult& result) {
  const CostReference& r = result.reference;
  const int unknowns = r.grid * r.grid * r.grid;
  md << fmt::format(
      "CHOLMOD's supernodal LL' (METIS ordering, one thread) of the 7-point Laplacian on a "
      "{0}^3 grid plus the identity ({1} unknowns, {2:.3f} GFLOP per numeric factorization): "
      "**{3:.4f} CPU s** ({4:.2f} GFLOP/s), the nearest-rank median of {5} factorizations; "
      "{6} before the trials (median {7:.4f} s) and {8} after them (median {9:.4f} s).\n\n",
      r.grid, unknowns, r.flops * 1e-9, r.seconds(), r.flops * 1e-9 / r.seconds(),
      r.start.size() + r.end.size(), r.start.size(), r.start_median(), r.end.size(),
      r.end_median());
  const CostMachine& m = result.machine;
  md << "Machine: " << m.cpu << ", " << m.cores << " logical core(s); load average (1, 5, 15 "
     << "min) " << m.load_start << " at the start, " << m.load_end
     << " at the end. CPU s are the process's (CLOCK_PROCESS_CPUTIME_ID), all on one thread; "
        "beside other work they still carry its cache and memory traffic, which the "
        "reference, timed in the same run, carries too.\n";
}

void write_csv(const fs::path& path, const CostResult& result) {
  std::ofstream csv(path);
  const double reference = result.reference.seconds();
  csv << std::setprecision(9)
      << "arm,gripper,objects,category,seed,candidate,verdict,cpu_s,cpu_reference_units,steps,"
         "newton_iterations";
  for (const std::string_view stage : kCostStages) csv << ',' << stage;
  csv << ",setup_cpu_s\n";
  for (const CostRun& run : result.runs) {
    const RobustnessTrial& t = run.trial;
    csv << run.arm << ',' << t.gripper << ',' << (t.soft ? "soft" : "rigid") << ',' << t.category
        << ',' << t.seed << ',' << t.candidate << ',' << verdict_of(t) << ',' << run.cpu_seconds
        << ',' << run.cpu_seconds / reference << ',' << t.newton.steps << ','
        << t.newton.iterations;
    for (const double seconds : run.stage_seconds()) csv << ',' << seconds;
    csv << ',' << run.setup_cpu_seconds << '\n';
  }
}

nlohmann::ordered_json statistics_json(const CostStatistics& s) {
  return {{"mean", s.mean}, {"median", s.median}, {"p90", s.p90}, {"max", s.max}};
}

}  // namespace

void write_cost_table(std::ostream& out, const std::vector<CostRow>& rows) {
  out << "| arm | verdict | n | mean CPU s | median | p90 | max | mean (reference units) | median "
         "| p90 | max |\n"
         "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const CostRow& row : rows) {
    out << "| " << row.arm << " | " << row.verdicts << " | " << row.cpu.n << " | "
        << statistics_text(row.cpu, 3) << " | " << statistics_text(row.reference, 2) << " |\n";
  }
  out << std::flush;
}

void write_cost_files(const fs::path& out, const CostResult& result,
                      const std::vector<CostRow>& rows) {
  fs::create_directories(out);
  std::ofstream md(out / "cost.md");
  md << "# grip bench cost\n\nWhat a farm pays per synthesized candidate: " << result.runs.size()
     << " candidates on " << result.shapes.size()
     << " shapes, each trial alone (its own trial::run_trials call on one thread, at the "
        "protocol's defaults), timed by the process's CPU time; "
     << fixed_or_dash(result.wall_seconds, 1) << " s wall in all"
     << (result.full_trials ? "; every trial ran its six gravity phases (--full-trials)"
                            : "; a trial stops once its verdict is decided")
     << ".\n\n";
  write_models(md, result);
  md << "\n## CPU seconds per candidate\n\nPer arm and verdict (\"failure\": every failure kind "
        "together): candidates, the mean, median, 90th percentile and largest CPU s, then the "
        "same in reference units (CPU s over the reference factorization's, below). Median and "
        "p90 by nearest rank: the value at rank ceil(q n) of the n values sorted ascending (for "
        "an even n the lower middle one).\n\n";
  write_cost_table(md, rows);
  md << "\n## Where the failing trials' time goes\n\nEach stage's share of the failing trials' "
        "wall time on their one thread, summed, %: the solver's stages are its own timers (wall "
        "s); protocol is what they leave: placement, servo, D1/D2, frames.\n\n";
  write_stage_table(md, result);
  md << "\n## Setup\n\nEach shape's object (meshed, if soft) and scene, built once for its "
        "candidates and not in the figures above (a gripper's first shape also builds the "
        "gripper's model, once per process); synthesis not included.\n\n";
  write_setup_table(md, result);
  md << "\n## Reference\n\n";
  write_reference(md, result);
  write_skipped_and_shortfalls(md, result.skipped, result.shortfalls);
  write_csv(out / "cost.csv", result);
}

void write_cost_json_line(std::ostream& out, const CostResult& result,
                          const std::vector<CostRow>& rows) {
  nlohmann::ordered_json arms = nlohmann::ordered_json::object();
  for (const CostRow& row : rows) {
    nlohmann::ordered_json figures = {{"candidates", row.cpu.n},
                                      {"cpu_seconds", statistics_json(row.cpu)},
                                      {"reference_units", statistics_json(row.reference)}};
    arms[row.arm][row.verdicts] = std::move(figures);
  }
  for (const std::string& arm : result.arms) {
    const std::array<double, kCostStages.size()> shares = stage_shares(failing_runs(result, arm));
    nlohmann::ordered_json stages = nlohmann::ordered_json::object();
    for (std::size_t i = 0; i < shares.size(); ++i) stages[std::string(kCostStages[i])] = shares[i];
    arms[arm]["failing_stage_shares"] = std::move(stages);
  }
  const CostReference& r = result.reference;
  const nlohmann::ordered_json line = {
      {"benchmark", "cost"},
      {"models", result.production_models ? "production" : "coarse"},
      {"full_trials", result.full_trials},
      {"candidates", result.runs.size()},
      {"reference_seconds", r.seconds()},
      {"reference_start_seconds", r.start_median()},
      {"reference_end_seconds", r.end_median()},
      {"reference_grid", r.grid},
      {"wall_seconds", result.wall_seconds},
      {"arms", std::move(arms)},
      {"skipped_seeds", result.skipped.size()},
      {"shortfalls", result.shortfalls.size()}};
  out << json::text(line, "%.6g") << '\n' << std::flush;
}

}  // namespace grip::bench
