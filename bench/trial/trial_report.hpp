#pragma once
// What `grip bench trial` reports: per arm the median cost of a trial (CPU and wall seconds,
// steps, Newton iterations, CPU per iteration), where its time went by solver stage, and the
// defaults' verdicts and slips against the reference; as text tables, trial.md, trial.csv (one
// row per run) and one JSON line.
#include <array>
#include <filesystem>
#include <limits>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "bench/trial/trial_benchmark.hpp"

namespace grip::bench {

// The solver's stages (solver::StageSeconds) and the rest of a trial, in the order of the tables
// and the CSV; "other" is TrialBenchRun::other_seconds.
inline constexpr std::array<std::string_view, 10> kTrialBenchStages = {
    "broad_phase", "derivatives", "assembly",     "factorization", "solve",
    "ccd",         "line_search", "friction_lag", "diagnostics",   "other"};

// A run's seconds in kTrialBenchStages' order.
std::array<double, kTrialBenchStages.size()> stage_seconds(const TrialBenchRun& run);

// An arm's figures at the defaults: each candidate's median over its repeats, then the median
// over the arm's candidates (NaN when none ran).
struct TrialBenchSummary {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  std::string arm;  // "fin-ray x soft"
  std::string gripper_model;
  std::string object_model;
  int candidates = 0;  // that ran at the defaults
  int runs = 0;        // at the defaults
  double cpu_seconds = nan;
  double wall_seconds = nan;
  double steps = nan;
  double iterations = nan;
  double cpu_per_iteration = nan;                         // s
  double cpu_total = 0.0;                                 // s: the candidates' medians summed
  std::array<double, kTrialBenchStages.size()> stages{};  // s
  // Every repeat of each candidate gave its first run's verdict, Newton statistics and slips.
  bool repeats_agree = true;
  int compared = 0;      // candidates run at the reference too
  int same_verdict = 0;  // held at both or at neither
  int same_failure_kind = 0;
  // m: the largest |slip at the defaults - slip at the reference| over the gravity phases that
  // ran at both, of the compared candidates held at both, and of all compared candidates (an
  // object that falls slips as far as it falls); NaN if none.
  double max_slip_difference_held = nan;
  double max_slip_difference = nan;
  double reference_cpu_seconds = nan;  // the median over the compared candidates
};

std::vector<TrialBenchSummary> trial_bench_summaries(const TrialBenchResult& result);

// The cost table and the stage table (each stage's share of the arm's median stage seconds
// summed, in %), Markdown.
void write_trial_bench_tables(std::ostream& out, const std::vector<TrialBenchSummary>& summaries);
// trial.md (settings, models, tables, candidates, shortfalls) and trial.csv in `out`, created
// if missing.
void write_trial_bench_files(const std::filesystem::path& out, const TrialBenchResult& result,
                             const std::vector<TrialBenchSummary>& summaries);
void write_trial_bench_json_line(std::ostream& out, const TrialBenchResult& result,
                                 const std::vector<TrialBenchSummary>& summaries);

}  // namespace grip::bench
