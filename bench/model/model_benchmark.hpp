#pragma once
// `grip bench model`: what modelling only what a scene needs saves (docs/results.md). Four
// comparisons of a lean model against the full one on the same squeeze-and-hold scene
// (squeeze_scene.hpp): a rigid cube as one affine body against stiff FEM, kinematic finger pads
// against stiff FEM pads pinned to kinematic jaws, a batch that freezes converged environments
// against one that keeps all iterating until the slowest converges, and no friction terms
// where mu = 0 against friction terms assembled anyway. Each: the variants run interleaved
// (median wall time of the repeats), their DOFs and Newton iterations, and the lean result's
// error against the full one.
#include <filesystem>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

#include "bench/model/squeeze_scene.hpp"

namespace grip::bench {

struct ModelBenchmarkOptions {
  int repeats = 5;       // runs per variant, interleaved; the table reports the median
  int threads = 1;       // of the batch comparison
  int batch_envs = 8;    // environments of the batch comparison, each cube placed its own way
  SqueezeOptions scene;  // the lean scene every comparison starts from
};

struct ModelComparison {
  std::string name;
  std::string lean;  // what the lean variant models
  std::string full;
  int lean_dofs = 0;  // DOFs solved for (over all environments for the batch)
  int full_dofs = 0;
  long lean_iterations = 0;  // Newton iterations (environment-iterations for the batch)
  long full_iterations = 0;
  std::vector<double> lean_runs;  // wall time of each repeat, s
  std::vector<double> full_runs;
  double lean_s = 0.0;  // medians
  double full_s = 0.0;
  // The process's CPU time of each repeat, and the medians: on a loaded machine (one thread)
  // steadier than wall time, which also counts the time other processes held the core.
  std::vector<double> lean_cpu_runs;
  std::vector<double> full_cpu_runs;
  double lean_cpu_s = 0.0;
  double full_cpu_s = 0.0;
  SqueezeError error;  // lean against full at the end (the largest over the batch's environments)
  double frozen_fraction = std::numeric_limits<double>::quiet_NaN();  // the batch's, frozen
  std::vector<double> vertex_errors_m;  // per environment of the batch (one elsewhere)
  std::string failure;                  // a variant's solver failure; empty when both ran through
  bool reproducible = true;             // every repeat of a variant ended in the same state
};

// Runs the four comparisons, logging each run's progress to `log`.
std::vector<ModelComparison> run_model_benchmark(const ModelBenchmarkOptions& options,
                                                 std::ostream& log);

// The comparisons as a markdown table.
void write_model_table(std::ostream& out, const std::vector<ModelComparison>& comparisons);
// One row per comparison, every figure and every repeat's time.
void write_model_csv(std::ostream& out, const std::vector<ModelComparison>& comparisons);

// Writes <out>/model.md, <out>/model.csv and, with Debian's python3 and matplotlib,
// <out>/model.png (bench/model/plot_model.py). False (with a warning) when there is no plot.
bool write_model_outputs(const std::filesystem::path& out,
                         const std::vector<ModelComparison>& comparisons,
                         const ModelBenchmarkOptions& options);

}  // namespace grip::bench
