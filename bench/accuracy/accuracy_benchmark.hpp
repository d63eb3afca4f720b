#pragma once
// `grip bench accuracy`: work-precision of the solver's settings on the standard trial scenes.
// One setting at a time is swept around the scene's defaults (dt, Newton tolerance, d_hat,
// kappa, eps_v, friction lag iterations, mesh resolution); every run is compared with a tight
// reference run of the same candidates (trial_error.hpp) and costed in wall time and Newton
// iterations; the Pareto front of (CPU time, error) says which settings are worth their cost.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "bench/accuracy/trial_error.hpp"

namespace grip::bench {

struct AccuracyOptions {
  std::vector<std::string> scenes;  // empty: every standard scene
  std::vector<std::string> sweeps;  // empty: every sweep (accuracy_sweep_names())
  int threads = 0;                  // per run; 0: all cores
  int repeats = 1;                  // runs per setting; the wall time is their median
  std::filesystem::path out = "out/accuracy";
};

// One run of a scene at one setting: a sweep's value (the others at the defaults), or the
// scene's reference (sweep "reference").
struct AccuracyRow {
  std::string scene;
  std::string sweep;
  double value = 0;
  bool is_default = false;
  double seconds = 0;                   // median wall time of the trials over the repeats
  double cpu_seconds = 0;               // median CPU time of the trials (all threads)
  std::vector<double> runs;             // every repeat's wall time
  std::uint64_t newton_iterations = 0;  // over every candidate
  std::uint64_t steps = 0;              // accepted time steps over every candidate
  int held = 0;                         // candidates held, by the reference's threshold
  RunError error;                       // against the scene's reference run
  bool on_sweep_front = false;          // on the (CPU time, translation error) front of its sweep
  bool on_scene_front = false;          // ... of every numerical setting of its scene (mesh aside)
};

// The sweeps' names, in order.
std::vector<std::string> accuracy_sweep_names();

// The reference's settings and every sweep's values, in words (for the tables).
std::string accuracy_settings_text();

// Runs every scene's reference and sweeps. Writes <out>/accuracy.csv and <out>/accuracy.md,
// and <out>/accuracy.png, <out>/accuracy_iterations.png when Debian's python3 with matplotlib
// is there. Throws std::invalid_argument for an unknown scene or sweep.
std::vector<AccuracyRow> run_accuracy(const AccuracyOptions& options);

}  // namespace grip::bench
