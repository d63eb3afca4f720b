#include "bench/trial/trial_report.hpp"

#include <spdlog/fmt/fmt.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "bench/common/table_text.hpp"
#include "io/candidate_record.hpp"
#include "src/json/json_text.hpp"

namespace grip::bench {
namespace fs = std::filesystem;
namespace {

constexpr std::size_t kStages = kTrialBenchStages.size();

// The stages as the tables head them.
constexpr std::array<std::string_view, kStages> kStageHeads = {
    "broad phase", "derivatives", "assembly",     "factorization", "solve",
    "CCD",         "line search", "friction lag", "diagnostics",   "protocol and other"};

double median(std::vector<double> values) {
  if (values.empty()) return TrialBenchSummary::nan;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
}

template <typename F>
double median_of(const std::vector<const TrialBenchRun*>& runs, F value) {
  std::vector<double> values;
  for (const TrialBenchRun* run : runs) values.push_back(value(*run));
  return median(values);
}

bool same_number(double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); }

// The same verdict, Newton statistics and slip per gravity phase.
bool same_answer(const TrialBenchRun& a, const TrialBenchRun& b) {
  for (std::size_t i = 0; i < a.displacement.size(); ++i) {
    if (!same_number(a.displacement[i], b.displacement[i])) return false;
  }
  return a.trial.status == b.trial.status && a.trial.failure == b.trial.failure &&
         a.trial.newton == b.trial.newton;
}

// `most` becomes `value` if that is larger or `most` is NaN; a NaN value changes nothing.
void keep_largest(double& most, double value) {
  if (!std::isnan(value)) most = std::isnan(most) ? value : std::max(most, value);
}

// The largest |a - b| over the phases measured in both; NaN if none was.
double largest_slip_difference(const TrialBenchRun& a, const TrialBenchRun& b) {
  double most = TrialBenchSummary::nan;
  for (std::size_t i = 0; i < a.displacement.size(); ++i) {
    keep_largest(most, std::abs(a.displacement[i] - b.displacement[i]));
  }
  return most;
}

// A candidate's runs: at the defaults in repeat order, and at the reference (null if none).
struct CandidateRuns {
  std::vector<const TrialBenchRun*> defaults;
  const TrialBenchRun* reference = nullptr;
};

std::vector<CandidateRuns> runs_by_candidate(const TrialBenchResult& result, std::size_t arm) {
  std::vector<CandidateRuns> by(result.arms[arm].candidates.size());
  for (const TrialBenchRun& run : result.runs) {
    if (run.slot.arm != arm) continue;
    CandidateRuns& c = by[run.slot.candidate];
    if (run.slot.reference) {
      c.reference = &run;
    } else {
      c.defaults.push_back(&run);
    }
  }
  return by;
}

TrialBenchSummary summarize(const TrialBenchResult& result, std::size_t a) {
  const TrialBenchArm& arm = result.arms[a];
  TrialBenchSummary s;
  s.arm = labels_arm_name(arm.arm);
  s.gripper_model = arm.gripper_model;
  s.object_model = arm.object_model;
  std::vector<double> cpu, wall, steps, iterations, per_iteration, reference_cpu;
  std::array<std::vector<double>, kStages> stages;
  for (const CandidateRuns& c : runs_by_candidate(result, a)) {
    if (c.defaults.empty()) continue;
    ++s.candidates;
    s.runs += static_cast<int>(c.defaults.size());
    cpu.push_back(median_of(c.defaults, [](const TrialBenchRun& r) { return r.cpu_seconds; }));
    wall.push_back(median_of(c.defaults, [](const TrialBenchRun& r) { return r.wall_seconds; }));
    steps.push_back(
        median_of(c.defaults, [](const TrialBenchRun& r) { return r.trial.newton.steps; }));
    iterations.push_back(
        median_of(c.defaults, [](const TrialBenchRun& r) { return r.trial.newton.iterations; }));
    if (iterations.back() > 0) per_iteration.push_back(cpu.back() / iterations.back());
    for (std::size_t i = 0; i < kStages; ++i) {
      stages[i].push_back(
          median_of(c.defaults, [i](const TrialBenchRun& r) { return stage_seconds(r)[i]; }));
    }
    for (const TrialBenchRun* run : c.defaults) {
      s.repeats_agree = s.repeats_agree && same_answer(*run, *c.defaults.front());
    }
    if (!c.reference) continue;
    const RobustnessTrial& d = c.defaults.front()->trial;
    const RobustnessTrial& r = c.reference->trial;
    ++s.compared;
    s.same_verdict += d.status == r.status;
    s.same_failure_kind += d.failure == r.failure;
    const double slip = largest_slip_difference(*c.defaults.front(), *c.reference);
    keep_largest(s.max_slip_difference, slip);
    if (d.status == io::Status::kSuccess && r.status == io::Status::kSuccess) {
      keep_largest(s.max_slip_difference_held, slip);
    }
    reference_cpu.push_back(c.reference->cpu_seconds);
  }
  s.cpu_seconds = median(cpu);
  s.wall_seconds = median(wall);
  s.steps = median(steps);
  s.iterations = median(iterations);
  s.cpu_per_iteration = median(per_iteration);
  for (const double c : cpu) s.cpu_total += c;
  for (std::size_t i = 0; i < kStages; ++i) s.stages[i] = median(stages[i]);
  s.reference_cpu_seconds = median(reference_cpu);
  return s;
}

std::string percent(double part, double whole) {
  return whole > 0 ? fixed_or_dash(100.0 * part / whole, 1) : "-";
}

std::string seconds_text(double s) { return fmt::format("{:.6g}", s); }

}  // namespace

std::array<double, kTrialBenchStages.size()> stage_seconds(const TrialBenchRun& run) {
  const solver::StageSeconds& s = run.stages;
  return {s.broad_phase, s.derivatives, s.assembly,     s.factorization, s.solve,
          s.ccd,         s.line_search, s.friction_lag, s.diagnostics,   run.other_seconds()};
}

std::vector<TrialBenchSummary> trial_bench_summaries(const TrialBenchResult& result) {
  std::vector<TrialBenchSummary> summaries;
  for (std::size_t a = 0; a < result.arms.size(); ++a) summaries.push_back(summarize(result, a));
  return summaries;
}

void write_trial_bench_tables(std::ostream& out, const std::vector<TrialBenchSummary>& summaries) {
  out << "| arm | candidates | runs | CPU s per trial | wall s per trial | steps | Newton "
         "iterations | CPU ms per iteration | CPU s, all candidates | repeats agree | CPU s per "
         "trial, reference | same verdict at the reference | same failure kind | largest slip "
         "difference (mm): held at both / all |\n"
         "|---|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|\n";
  for (const TrialBenchSummary& s : summaries) {
    out << "| " << s.arm << " | " << s.candidates << " | " << s.runs << " | "
        << fixed_or_dash(s.cpu_seconds, 2) << " | " << fixed_or_dash(s.wall_seconds, 2) << " | "
        << fixed_or_dash(s.steps, 0) << " | " << fixed_or_dash(s.iterations, 0) << " | "
        << fixed_or_dash(s.cpu_per_iteration * 1e3, 2) << " | " << fixed_or_dash(s.cpu_total, 2)
        << " | " << (s.repeats_agree ? "yes" : "no") << " | "
        << fixed_or_dash(s.reference_cpu_seconds, 2) << " | "
        << (s.compared ? std::to_string(s.same_verdict) + " of " + std::to_string(s.compared) : "-")
        << " | " << (s.compared ? std::to_string(s.same_failure_kind) : "-") << " | "
        << fixed_or_dash(s.max_slip_difference_held * 1e3, 4) << " / "
        << fixed_or_dash(s.max_slip_difference * 1e3, 4) << " |\n";
  }
  out << "\nWhere a trial's time went, % of the median seconds per stage summed:\n\n| arm |";
  for (const std::string_view head : kStageHeads) out << ' ' << head << " |";
  out << " summed (s) |\n|---|";
  for (std::size_t i = 0; i <= kStages; ++i) out << "---:|";
  out << '\n';
  for (const TrialBenchSummary& s : summaries) {
    double total = 0.0;
    for (const double v : s.stages) total += v;
    out << "| " << s.arm << " |";
    for (const double v : s.stages) out << ' ' << percent(v, total) << " |";
    out << ' ' << fixed_or_dash(s.candidates ? total : TrialBenchSummary::nan, 2) << " |\n";
  }
}

namespace {

void write_settings(std::ostream& md, const TrialBenchResult& result) {
  const trial::TrialParameters& d = result.defaults;
  const trial::TrialParameters& r = result.reference;
  md << "# grip bench trial\n\nEach trial alone on one thread (a batch of one), its scene "
        "built before. CPU: the thread's time over the trial. Per arm: each candidate's median "
     << "over " << result.repeats
     << " repeat(s) at the defaults (interleaved across arms), then the median over the arm's "
        "candidates. Defaults: dt "
     << d.sim.dt << " s, newton_tol " << d.sim.newton_tol << ", " << d.sim.friction_lag_iterations
     << " friction lag iteration(s). ";
  if (result.reference_run) {
    md << "Reference, as `grip bench labels`'s: dt " << r.sim.dt << " s, newton_tol "
       << r.sim.newton_tol << ", " << r.sim.friction_lag_iterations
       << " friction lag iterations, the same verdict threshold ("
       << r.displacement_threshold() * 1e3
       << " mm plus eps_v x the time under gravity), each candidate once; the same verdict is held "
          "at both or at neither. ";
  } else {
    md << "No reference runs. ";
  }
  md << fixed_or_dash(result.wall_seconds / 60, 1) << " min in all.\n\n";
}

void write_arms(std::ostream& md, const TrialBenchResult& result) {
  md << "\nModels and candidates:\n\n";
  for (const TrialBenchArm& arm : result.arms) {
    md << "- " << labels_arm_name(arm.arm) << ": " << arm.gripper_model << "; objects "
       << arm.object_model << ". Candidates:";
    for (const TrialBenchCandidate& c : arm.candidates) {
      md << ' ' << c.category << " seed " << c.seed << " #" << c.candidate
         << (&c == &arm.candidates.back() ? "." : ",");
    }
    if (arm.candidates.empty()) md << " none.";
    md << '\n';
    for (const std::string& s : arm.shortfalls) md << "  - shortfall: " << s << '\n';
  }
}

void write_csv(std::ostream& csv, const TrialBenchResult& result) {
  csv << "arm,category,seed,candidate,settings,repeat,cpu_s,process_cpu_s,wall_s,steps,"
         "newton_iterations,retries";
  for (const std::string_view stage : kTrialBenchStages) csv << ',' << stage << "_s";
  csv << ",factorizations,reused_factorizations,cg_iterations,verdict,slip_mm\n";
  for (const TrialBenchRun& run : result.runs) {
    const TrialBenchArm& arm = result.arms[run.slot.arm];
    const TrialBenchCandidate& c = arm.candidates[run.slot.candidate];
    csv << labels_arm_name(arm.arm) << ',' << c.category << ',' << c.seed << ',' << c.candidate
        << ',' << (run.slot.reference ? "reference" : "defaults") << ',' << run.slot.repeat << ','
        << seconds_text(run.cpu_seconds) << ',' << seconds_text(run.process_cpu_seconds) << ','
        << seconds_text(run.wall_seconds) << ',' << run.trial.newton.steps << ','
        << run.trial.newton.iterations << ',' << run.trial.newton.retries;
    for (const double s : stage_seconds(run)) csv << ',' << seconds_text(s);
    csv << ',' << run.linear_solves.factorizations << ',' << run.linear_solves.reused << ','
        << run.linear_solves.cg_iterations;
    csv << ',' << verdict_of(run.trial) << ',' << fixed_or_dash(run.trial.largest_slip * 1e3, 4)
        << '\n';
  }
}

}  // namespace

void write_trial_bench_files(const fs::path& out, const TrialBenchResult& result,
                             const std::vector<TrialBenchSummary>& summaries) {
  fs::create_directories(out);
  std::ofstream md(out / "trial.md");
  write_settings(md, result);
  write_trial_bench_tables(md, summaries);
  write_arms(md, result);
  std::ofstream csv(out / "trial.csv");
  write_csv(csv, result);
}

void write_trial_bench_json_line(std::ostream& out, const TrialBenchResult& result,
                                 const std::vector<TrialBenchSummary>& summaries) {
  nlohmann::ordered_json arms = nlohmann::ordered_json::array();
  for (const TrialBenchSummary& s : summaries) {
    nlohmann::ordered_json stages = nlohmann::ordered_json::object();
    for (std::size_t i = 0; i < kStages; ++i)
      stages[std::string(kTrialBenchStages[i])] = s.stages[i];
    arms.push_back({{"arm", s.arm},
                    {"gripper_model", s.gripper_model},
                    {"object_model", s.object_model},
                    {"candidates", s.candidates},
                    {"runs", s.runs},
                    {"cpu_seconds", s.cpu_seconds},
                    {"wall_seconds", s.wall_seconds},
                    {"steps", s.steps},
                    {"newton_iterations", s.iterations},
                    {"cpu_seconds_per_iteration", s.cpu_per_iteration},
                    {"cpu_seconds_all_candidates", s.cpu_total},
                    {"stage_seconds", std::move(stages)},
                    {"repeats_agree", s.repeats_agree},
                    {"compared", s.compared},
                    {"same_verdict", s.same_verdict},
                    {"same_failure_kind", s.same_failure_kind},
                    {"max_slip_difference_held", s.max_slip_difference_held},
                    {"max_slip_difference", s.max_slip_difference},
                    {"reference_cpu_seconds", s.reference_cpu_seconds}});
  }
  const nlohmann::ordered_json root = {{"benchmark", "trial"},
                                       {"repeats", result.repeats},
                                       {"reference", result.reference_run},
                                       {"wall_seconds", result.wall_seconds},
                                       {"arms", std::move(arms)}};
  out << json::text(root, "%.6g") << '\n' << std::flush;
}

}  // namespace grip::bench
