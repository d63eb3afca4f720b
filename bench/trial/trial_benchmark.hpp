#pragma once
// `grip bench trial`: what one grasp trial costs, per gripper x object model, so that speed-ups
// of the engine show at the same answers. A fixed set of synthesized candidates per arm runs
// trial by trial on one thread, `repeats` times, interleaved across arms; per trial the thread's
// CPU time, the wall time, steps, Newton iterations and where the solver's time went, and each
// candidate once at `grip bench labels`' reference, whose verdicts and slips the defaults' are
// compared with.
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "bench/labels/labels_benchmark.hpp"
#include "bench/robustness/robustness_benchmark.hpp"
#include "solver/newton/diagnostics.hpp"
#include "src/trial/trial_parameters.hpp"

namespace grip::bench {

struct TrialBenchOptions {
  // Empty: parallel-jaw x rigid, fin-ray x rigid, fin-ray x soft, leap x rigid, leap x soft.
  std::vector<LabelsArm> arms;
  std::vector<std::string> categories;  // empty: kLabelsCategories
  int candidates = 0;                   // per arm; 0: trial_bench_candidates(arm)
  int repeats = 3;                      // runs of each candidate at the defaults
  bool reference = true;                // each candidate once more at reference_parameters
  // The models `grip trial` and the farm simulate, so that the table is what a farm pays; false:
  // the robustness benchmark's coarse ones (RobustnessOptions::production_models).
  bool production_models = true;
  std::filesystem::path out = "out/bench-trial";
};

// The candidates an arm runs by default: 8 for rigid jaws on rigid objects (a trial takes a
// fraction of a second), 4 for the hand on rigid objects, 2 for the others (a coarse fin-ray
// trial or a soft object's takes a minute or more).
int trial_bench_candidates(const LabelsArm& arm);

// One candidate of an arm: the k-th synthesized on the shape of `category` and `seed`.
struct TrialBenchCandidate {
  std::string category;
  std::uint64_t seed = 0;
  std::uint64_t candidate = 0;
};

// An arm as planned: its models in words and its candidates. Candidate i is on the category
// i mod C (C categories), the (i / C)-th candidate of that category's first shape (seeds 1, 2,
// ... up to kSeedsTriedPerShape) that gets one.
struct TrialBenchArm {
  LabelsArm arm;
  std::string gripper_model;  // robustness_gripper_model
  std::string object_model;   // robustness_object_model
  std::vector<TrialBenchCandidate> candidates;
  std::vector<std::string> shortfalls;  // categories without a shape, or fewer candidates
};

// One run of the schedule: a candidate of an arm, at the defaults (repeat 1, 2, ...) or at the
// reference.
struct TrialBenchSlot {
  std::size_t arm = 0;
  std::size_t candidate = 0;  // index in the arm's candidates
  int repeat = 1;             // 1 at the reference
  bool reference = false;
};

// Repeat by repeat, then the reference round; within a round candidate index by candidate index,
// and for each index arm by arm (an arm with fewer candidates sits the later indices out), so
// that the machine's load falls on every arm alike.
std::vector<TrialBenchSlot> trial_bench_schedule(const std::vector<std::size_t>& candidates,
                                                 int repeats, bool reference);

struct TrialBenchRun {
  TrialBenchSlot slot;
  RobustnessTrial trial;                    // verdict, Newton statistics, largest slip
  std::array<double, 6> displacement{};     // m, the record's slip per gravity phase (NaN: not run)
  double cpu_seconds = 0.0;                 // the running thread's CPU time
  double process_cpu_seconds = 0.0;         // every thread of the process
  double wall_seconds = 0.0;                // the trial alone, its scene built before
  solver::StageSeconds stages;              // the solver's (trial::TrialOutcome::stage_seconds)
  solver::LinearSolveCounts linear_solves;  // trial::TrialOutcome::linear_solves

  // The protocol's own work (placement, servo, verdict, metrics) and everything not timed by
  // a stage.
  double other_seconds() const { return wall_seconds - stages.total(); }
};

struct TrialBenchResult {
  std::vector<TrialBenchArm> arms;
  std::vector<TrialBenchRun> runs;  // in the order they ran
  trial::TrialParameters defaults;
  trial::TrialParameters reference;
  int repeats = 0;
  bool reference_run = false;
  double wall_seconds = 0.0;  // synthesis and object preparation included
};

// Throws std::invalid_argument, naming the command, for an unknown gripper or category,
// candidates below 0 or repeats below 1.
void check_trial_bench_options(const TrialBenchOptions& options);

// Plans the arms (synthesis, objects, scenes), then runs the schedule one trial at a time on
// the calling thread. Logs one line per run.
TrialBenchResult run_trial_bench(const TrialBenchOptions& options);

}  // namespace grip::bench
