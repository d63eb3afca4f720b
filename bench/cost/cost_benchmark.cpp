#include "bench/cost/cost_benchmark.hpp"

#include <spdlog/spdlog.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <exception>
#include <fstream>
#include <map>
#include <memory>
#include <stdexcept>
#include <thread>
#include <tuple>

#include "bench/common/cpu_clock.hpp"
#include "bench/cost/cost_statistics.hpp"
#include "bench/labels/labels_benchmark.hpp"
#include "bench/robustness/robustness_trials.hpp"
#include "solver/linear/blas_threads.hpp"
#include "solver/linear/sparse_cholesky.hpp"
#include "src/synth/candidate.hpp"
#include "src/trial/trial_outcome.hpp"
#include "src/trial/trial_parameters.hpp"

namespace grip::bench {
namespace {

std::string describe(const RobustnessSet& set, std::uint64_t seed) {
  return set.gripper + " x " + set.category + " seed " + std::to_string(seed) +
         (set.soft ? " soft" : " rigid");
}

std::string cpu_model() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);) {
    if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos) {
      return line.substr(line.find(':') + 2);
    }
  }
  return "unknown CPU";
}

// The 1, 5 and 15 minute load averages: how busy the machine was beside this run.
std::string load_average() {
  std::ifstream loadavg("/proc/loadavg");
  std::string one, five, fifteen;
  loadavg >> one >> five >> fifteen;
  return one + " " + five + " " + fifteen;
}

// The seed walk, shape by shape, into the result.
class CostRunner {
 public:
  CostRunner(CostResult& result, const trial::TrialParameters& parameters)
      : result_(result), parameters_(parameters) {}

  // The first set.seeds seeds (of 1 .. kSeedsTriedPerShape x seeds) whose shape gets a
  // candidate, as run_robustness walks them.
  void walk_seeds(const RobustnessSet& set) {
    const std::uint64_t last_seed = static_cast<std::uint64_t>(kSeedsTriedPerShape) * set.seeds;
    int found = 0;
    for (std::uint64_t seed = 1; seed <= last_seed && found < set.seeds; ++seed) {
      const std::vector<synth::Candidate>& candidates = synthesized(set, seed);
      if (candidates.empty()) {
        result_.skipped.push_back(describe(set, seed));
        spdlog::info("cost: {}: no candidate, shape skipped", describe(set, seed));
        continue;
      }
      ++found;
      if (static_cast<int>(candidates.size()) < set.candidates) {
        shortfall(describe(set, seed) + ": " + std::to_string(candidates.size()) + " of " +
                  std::to_string(set.candidates) + " candidates synthesized");
      }
      run_shape(set, seed, candidates);
    }
    if (found < set.seeds) {
      shortfall(cost_arm_name(set.gripper, set.soft) + " x " + set.category + ": " +
                std::to_string(found) + " of " + std::to_string(set.seeds) + " shapes in seeds 1-" +
                std::to_string(last_seed));
    }
  }

 private:
  // A rigid and a soft set of one gripper and category share their seeds' candidates.
  const std::vector<synth::Candidate>& synthesized(const RobustnessSet& set, std::uint64_t seed) {
    const auto key = std::make_tuple(set.gripper, set.category, seed);
    auto it = candidates_.find(key);
    if (it == candidates_.end()) {
      it = candidates_.emplace(key, synthesize_candidates(set, seed, set.candidates)).first;
    }
    return it->second;
  }

  void shortfall(std::string text) {
    spdlog::warn("cost: {}", text);
    result_.shortfalls.push_back(std::move(text));
  }

  // The shape's object and scene, built once and timed as its setup, then each candidate alone.
  void run_shape(const RobustnessSet& set, std::uint64_t seed,
                 const std::vector<synth::Candidate>& candidates) {
    const std::string arm = cost_arm_name(set.gripper, set.soft);
    const double setup_start = process_cpu_seconds();
    std::unique_ptr<RobustnessScene> scene;
    try {
      scene = std::make_unique<RobustnessScene>(set, make_object(set, seed), parameters_);
    } catch (const std::exception& e) {
      shortfall(describe(set, seed) + ": no trials (" + e.what() + ")");
      return;
    }
    const double setup = process_cpu_seconds() - setup_start;
    result_.shapes.push_back({arm, set.category, seed, static_cast<int>(candidates.size()), setup});
    if (std::find(result_.arms.begin(), result_.arms.end(), arm) == result_.arms.end()) {
      result_.arms.push_back(arm);
    }
    for (std::size_t k = 0; k < candidates.size(); ++k) {
      try {
        result_.runs.push_back(run_candidate(set, seed, k, candidates[k], *scene));
      } catch (const std::exception& e) {  // a candidate the gripper cannot take
        shortfall(describe(set, seed) + " candidate " + std::to_string(k) + ": no trial (" +
                  e.what() + ")");
        continue;
      }
      CostRun& run = result_.runs.back();
      run.setup_cpu_seconds = setup;
      spdlog::info("cost: {} candidate {}: {:.3f} CPU s, {} steps, {} iterations, {}",
                   describe(set, seed), k, run.cpu_seconds, run.trial.newton.steps,
                   run.trial.newton.iterations, verdict_of(run.trial));
    }
  }

  // One candidate as the farm runs it, alone: its own run_trials call on one thread.
  CostRun run_candidate(const RobustnessSet& set, std::uint64_t seed, std::size_t k,
                        const synth::Candidate& candidate, const RobustnessScene& scene) const {
    const std::vector<synth::Candidate> one = {candidate};
    const double start = process_cpu_seconds();
    const auto wall_start = std::chrono::steady_clock::now();
    const std::vector<trial::TrialOutcome> outcomes = scene.run(one, 1, result_.full_trials);
    CostRun run;
    run.cpu_seconds = process_cpu_seconds() - start;
    run.wall_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    run.arm = cost_arm_name(set.gripper, set.soft);
    run.trial = robustness_trial(set, seed, k, outcomes.front(), scene.parameters());
    run.stages = outcomes.front().stage_seconds;
    return run;
  }

  CostResult& result_;
  const trial::TrialParameters& parameters_;
  std::map<std::tuple<std::string, std::string, std::uint64_t>, std::vector<synth::Candidate>>
      candidates_;
};

}  // namespace

std::vector<RobustnessSet> plan_cost(const CostOptions& options) {
  if (options.seeds < 1 || options.candidates < 1) {
    throw std::invalid_argument("--seeds and --candidates must be at least 1");
  }
  if (options.reference_repeats < 1) {
    throw std::invalid_argument("--reference-repeats must be at least 1");
  }
  RobustnessOptions o;
  o.grippers = options.grippers.empty() ? kCostGrippers : options.grippers;
  o.categories = options.categories.empty() ? kLabelsCategories : options.categories;
  o.seeds = options.seeds;
  o.candidates = options.candidates;
  o.rigid = options.rigid;
  o.soft = options.soft;
  o.production_models = options.production_models;
  return plan_robustness(o);
}

std::string cost_arm_name(const std::string& gripper, bool soft) {
  return gripper + (soft ? " x soft" : " x rigid");
}

Eigen::SparseMatrix<double> reference_matrix(int grid) {
  const auto id = [grid](int i, int j, int k) { return (i * grid + j) * grid + k; };
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < grid; ++i) {
    for (int j = 0; j < grid; ++j) {
      for (int k = 0; k < grid; ++k) {
        const int row = id(i, j, k);
        entries.emplace_back(row, row, 7.0);  // 6 neighbours' Laplacian, plus the identity
        if (i + 1 < grid) entries.emplace_back(id(i + 1, j, k), row, -1.0);
        if (j + 1 < grid) entries.emplace_back(id(i, j + 1, k), row, -1.0);
        if (k + 1 < grid) entries.emplace_back(id(i, j, k + 1), row, -1.0);
      }
    }
  }
  const int size = grid * grid * grid;
  Eigen::SparseMatrix<double> lower(size, size);
  lower.setFromTriplets(entries.begin(), entries.end());
  lower.makeCompressed();
  return lower;
}

std::vector<double> time_reference_factorizations(int grid, int repeats, double& flops) {
  solver::use_single_threaded_blas();  // as every environment does
  const Eigen::SparseMatrix<double> matrix = reference_matrix(grid);
  solver::SparseCholesky cholesky;
  // The first factorization also analyses the pattern: not timed.
  if (!cholesky.factorize(matrix)) throw std::logic_error("the reference matrix is not SPD");
  flops = cholesky.factor_flops();
  std::vector<double> seconds;
  for (int r = 0; r < repeats; ++r) {
    const double start = process_cpu_seconds();
    cholesky.factorize(matrix);
    seconds.push_back(process_cpu_seconds() - start);
  }
  return seconds;
}

double CostReference::seconds() const {
  std::vector<double> all = start;
  all.insert(all.end(), end.begin(), end.end());
  return nearest_rank(all, 0.5);
}

double CostReference::start_median() const { return nearest_rank(start, 0.5); }
double CostReference::end_median() const { return nearest_rank(end, 0.5); }

std::array<double, kCostStages.size()> CostRun::stage_seconds() const {
  const solver::StageSeconds& s = stages;
  return {s.broad_phase, s.derivatives, s.assembly,     s.factorization, s.solve,
          s.ccd,         s.line_search, s.friction_lag, s.diagnostics,   protocol_seconds()};
}

CostResult run_cost(const CostOptions& options) {
  CostResult result;
  result.sets = plan_cost(options);
  result.production_models = options.production_models;
  result.full_trials = options.full_trials;
  result.machine = {cpu_model(), std::thread::hardware_concurrency(), load_average(), ""};
  const auto start = std::chrono::steady_clock::now();
  const trial::TrialParameters parameters;  // the protocol's and the solver's defaults
  CostRunner runner(result, parameters);
  // Everything on this thread: no pool thread spins on the process's CPU clock beside a trial.
  tbb::task_arena(1).execute([&] {
    CostReference& reference = result.reference;
    reference.start =
        time_reference_factorizations(reference.grid, options.reference_repeats, reference.flops);
    for (const RobustnessSet& set : result.sets) runner.walk_seeds(set);
    reference.end =
        time_reference_factorizations(reference.grid, options.reference_repeats, reference.flops);
  });
  result.machine.load_end = load_average();
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace grip::bench
