#pragma once
// `grip bench cost`: what a farm pays per synthesized candidate. A farm runs every candidate the
// synthesis gives, held or not, and a failing trial (displaced, lost_contact) runs its gravity
// phases to the end or waits for the object to come to rest: it can cost many times a held one.
// Each candidate runs alone, timed by the process's CPU time, and every figure is also given in
// units of a fixed CHOLMOD factorization timed in the same run, so that two machines compare.
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/SparseCore>

#include "bench/robustness/robustness_benchmark.hpp"
#include "solver/newton/diagnostics.hpp"

namespace grip::bench {

// The grippers the benchmark knows, and its default.
inline const std::vector<std::string> kCostGrippers = {"parallel-jaw", "fin-ray", "leap"};

struct CostOptions {
  std::vector<std::string> grippers;    // empty: kCostGrippers
  std::vector<std::string> categories;  // empty: kLabelsCategories
  int seeds = 1;                        // shapes per category, as robustness walks the seeds
  int candidates = 8;                   // synthesized per shape
  bool rigid = true;
  bool soft = false;  // soft trials cost minutes each: only when asked for
  // The models the farm simulates (RobustnessOptions::production_models); false: the coarse ones.
  bool production_models = true;
  int reference_repeats = 9;  // reference factorizations timed at the start, and again at the end
  // Run decided trials to the end (trial::TrialRunOptions::full_trials): the same verdicts, at
  // what the protocol cost before trials stopped once decided.
  bool full_trials = false;
  std::filesystem::path out = "out/cost";
};

// The sets the options ask for (plan_robustness's: gripper by gripper, then category, rigid
// before soft). Throws std::invalid_argument for an unknown gripper or category, seeds,
// candidates or reference repeats below 1, or neither rigid nor soft objects.
std::vector<RobustnessSet> plan_cost(const CostOptions& options);

// "fin-ray x soft": a gripper and an object model, what the tables group by.
std::string cost_arm_name(const std::string& gripper, bool soft);

// The in-run reference: CHOLMOD's supernodal LL' (METIS ordering, one thread) of the 7-point
// Laplacian on a kReferenceGrid^3 grid plus the identity: 0.37 GFLOP, 30-50 ms on the 2-core
// development machine. The matrix and the factorization are the same on every machine, so a
// trial's CPU seconds over this one's compare across machines where seconds alone do not.
inline constexpr int kReferenceGrid = 22;
Eigen::SparseMatrix<double> reference_matrix(int grid);

struct CostReference {
  int grid = kReferenceGrid;
  double flops = 0.0;         // of one numeric factorization, by CHOLMOD's analysis
  std::vector<double> start;  // CPU s of each factorization timed before the trials
  std::vector<double> end;    // and after them
  double seconds() const;     // nearest-rank median of start and end together
  double start_median() const;
  double end_median() const;
};

// `repeats` numeric factorizations of reference_matrix(grid), each timed by the process's CPU
// time, after one untimed that analyses the pattern; `flops` gets CHOLMOD's count for one.
std::vector<double> time_reference_factorizations(int grid, int repeats, double& flops);

// The solver's stages (solver::StageSeconds) and the protocol's own work, in the CSV's and the
// tables' order.
inline constexpr std::array<std::string_view, 10> kCostStages = {
    "broad_phase", "derivatives", "assembly",     "factorization", "solve",
    "ccd",         "line_search", "friction_lag", "diagnostics",   "protocol"};

// One candidate's trial, run alone.
struct CostRun {
  std::string arm;                 // cost_arm_name
  RobustnessTrial trial;           // category, seed, candidate index, verdict, Newton statistics
  double cpu_seconds = 0.0;        // the process's CPU time over its trial::run_trials call
  double wall_seconds = 0.0;       // and the wall time: the stages' own clock
  solver::StageSeconds stages;     // trial::TrialOutcome::stage_seconds (wall s, one thread)
  double setup_cpu_seconds = 0.0;  // its shape's object and scene, built once for its candidates

  // The protocol's own work (placement, servo, D1/D2, frames) and anything no stage times, in
  // wall s as the stages are: beside other work, CPU s less wall s could go below zero.
  double protocol_seconds() const { return wall_seconds - stages.total(); }
  std::array<double, kCostStages.size()> stage_seconds() const;
};

// One shape of an arm: its object and scene, built once for every candidate on it.
struct CostShape {
  std::string arm;
  std::string category;
  std::uint64_t seed = 0;
  int candidates = 0;  // synthesized
  double setup_cpu_seconds = 0.0;
};

// Where the run happened, for reading its seconds.
struct CostMachine {
  std::string cpu;  // /proc/cpuinfo's model name
  unsigned cores = 0;
  std::string load_start;  // /proc/loadavg's 1, 5 and 15 minute averages
  std::string load_end;
};

struct CostResult {
  std::vector<RobustnessSet> sets;      // the plan
  std::vector<std::string> arms;        // in the order they ran
  std::vector<CostShape> shapes;        // in the order they ran
  std::vector<CostRun> runs;            // shape by shape, candidates in order
  std::vector<std::string> skipped;     // "parallel-jaw x box seed 1 rigid": no candidate
  std::vector<std::string> shortfalls;  // fewer shapes or candidates than asked, in words
  CostReference reference;
  CostMachine machine;
  bool production_models = true;
  bool full_trials = false;  // CostOptions::full_trials
  double wall_seconds = 0.0;
};

// Runs the plan on one thread: the reference, then per set the seed walk (synthesis, the
// shape's object and scene, each candidate alone), then the reference again. Logs one line per
// candidate.
CostResult run_cost(const CostOptions& options);

}  // namespace grip::bench
