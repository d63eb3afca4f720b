#include "bench/robustness/robustness_benchmark.hpp"

#include <spdlog/spdlog.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <span>
#include <stdexcept>

#include "bench/robustness/robustness_trials.hpp"
#include "src/grippers/fin_ray_finger.hpp"
#include "src/objects/object_library.hpp"

namespace grip::bench {
namespace {

// How many seeds and candidates per (object, gripper) a gripper runs by default, for rigid and
// for soft objects: at least 384 parallel-jaw trials and 48 each of fin-ray and hand trials.
// One candidate per soft object: a soft cup or bowl (walls of 4-8 mm) costs minutes per trial
// even at this benchmark's coarse mesh (robustness_object_model), and a soft batch's trials share
// one object, so more of them say little new.
struct GripperDefaults {
  std::string_view name;
  int rigid_seeds, rigid_candidates;
  int soft_seeds, soft_candidates;
};

constexpr GripperDefaults kDefaults[] = {
    {"parallel-jaw", 4, 8, 1, 1},
    {"fin-ray", 1, 3, 1, 1},
    {"leap", 1, 3, 1, 1},
};

const GripperDefaults& defaults_of(const std::string& name) {
  for (const GripperDefaults& d : kDefaults) {
    if (d.name == name) return d;
  }
  std::string known;
  for (const GripperDefaults& d : kDefaults)
    known += (known.empty() ? "" : ", ") + std::string(d.name);
  throw std::invalid_argument("unknown gripper '" + name + "' (" + known + ")");
}

std::string describe(const RobustnessSet& set, std::uint64_t seed) {
  return set.gripper + " x " + set.category + " seed " + std::to_string(seed) +
         (set.soft ? " soft" : " rigid");
}

// The seed walk of one gripper and category, batch by batch, into the result.
struct CategoryRun {
  RobustnessResult& result;
  const trial::TrialParameters& parameters;
  bool full_trials = false;  // RobustnessOptions::full_trials
  tbb::task_arena arena;

  // Candidates for the seed's shape, `count` asked, as `grip synth` makes them.
  std::vector<synth::Candidate> synthesize(const RobustnessSet& set, std::uint64_t seed,
                                           int count) {
    std::vector<synth::Candidate> candidates;
    arena.execute([&] { candidates = synthesize_candidates(set, seed, count); });
    return candidates;
  }

  // One batch: the object prepared, every candidate's trial, the log line.
  void batch(const RobustnessSet& set, std::uint64_t seed,
             const std::vector<synth::Candidate>& candidates) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<trial::TrialOutcome> outcomes;
    try {
      trial::TrialObject object;
      arena.execute([&] { object = make_object(set, seed); });
      outcomes =
          RobustnessScene(set, object, parameters).run(candidates, result.threads, full_trials);
    } catch (const std::exception& e) {
      // An object that cannot be meshed or a candidate the gripper cannot take: reported, and
      // the other batches still run.
      result.shortfalls.push_back(describe(set, seed) + ": no trials (" + e.what() + ")");
      spdlog::warn("{}", result.shortfalls.back());
      return;
    }
    result.batches.push_back(
        {set.gripper, set.category, seed, set.soft, static_cast<int>(outcomes.size())});
    std::map<io::FailureKind, int> counts;
    for (std::size_t k = 0; k < outcomes.size(); ++k) {
      result.trials.push_back(robustness_trial(set, seed, k, outcomes[k], parameters));
      ++counts[result.trials.back().failure];
    }
    std::string summary;
    for (const auto& [kind, n] : counts) {
      summary += (summary.empty() ? "" : ", ") + std::to_string(n) + " " +
                 std::string(kind == io::FailureKind::kNone ? "success" : io::to_string(kind));
    }
    spdlog::info("{}: {} trial(s) in {:.1f} s: {}", describe(set, seed), outcomes.size(),
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                 summary);
  }

  // Sets [first, last) of result.sets: one gripper and category.
  void walk_seeds(std::size_t first, std::size_t last) {
    const std::span<const RobustnessSet> sets(result.sets.data() + first, last - first);
    std::vector<int> found(sets.size(), 0);
    int most = 0;
    for (const RobustnessSet& set : sets) most = std::max(most, set.seeds);
    const std::uint64_t last_seed = static_cast<std::uint64_t>(kSeedsTriedPerShape) * most;
    const auto done = [&] {
      for (std::size_t k = 0; k < sets.size(); ++k) {
        if (found[k] < sets[k].seeds) return false;
      }
      return true;
    };
    for (std::uint64_t seed = 1; seed <= last_seed && !done(); ++seed) {
      std::map<int, std::vector<synth::Candidate>> by_count;  // this seed's, per count
      for (std::size_t k = 0; k < sets.size(); ++k) {
        const RobustnessSet& set = sets[k];
        if (found[k] >= set.seeds) continue;
        auto it = by_count.find(set.candidates);
        if (it == by_count.end()) {
          it = by_count.emplace(set.candidates, synthesize(set, seed, set.candidates)).first;
        }
        if (it->second.empty()) {
          result.skipped.push_back(describe(set, seed));
          spdlog::info("{}: no candidate, shape skipped", describe(set, seed));
          continue;
        }
        ++found[k];
        if (static_cast<int>(it->second.size()) < set.candidates) {
          result.shortfalls.push_back(describe(set, seed) + ": " +
                                      std::to_string(it->second.size()) + " of " +
                                      std::to_string(set.candidates) + " candidates synthesized");
        }
        batch(set, seed, it->second);
      }
    }
    for (std::size_t k = 0; k < sets.size(); ++k) {
      if (found[k] < sets[k].seeds) {
        result.shortfalls.push_back(
            sets[k].gripper + " x " + sets[k].category + (sets[k].soft ? " soft" : " rigid") +
            ": " + std::to_string(found[k]) + " of " + std::to_string(sets[k].seeds) +
            " shapes in seeds 1-" + std::to_string(last_seed));
      }
    }
  }
};

}  // namespace

std::string verdict_of(const RobustnessTrial& trial) {
  return trial.failure == io::FailureKind::kNone ? "success"
                                                 : std::string(io::to_string(trial.failure));
}

std::string robustness_gripper_model(const std::string& gripper, bool production_models) {
  if (gripper == "parallel-jaw") return "rigid box jaws (the registry's parallel-jaw)";
  if (production_models) {
    std::string model = "the registry's ";  // appended: GCC 12 warns falsely on a + chain
    model += gripper;
    model += ", as grip trial builds it";
    return model;
  }
  if (gripper == "fin-ray")
    return "fin-ray fingers with 1 tet layer across the depth (4 in production)";
  if (gripper == "leap") return "LEAP hand with 8-sided capsule links (coarse_leap_hand)";
  return gripper;
}

std::string fine_fin_ray_model() {
  const grippers::FinRayOptions production;
  return fmt::format("{} tet layers and {:g} mm profile edges (production: {} and {:g} mm)",
                     kFineFinRayLayers, kFineFinRayEdge * 1e3, production.layers,
                     production.edge_length * 1e3);
}

std::vector<std::string> robustness_categories(const std::vector<std::string>& categories) {
  if (!categories.empty()) return categories;
  std::vector<std::string> all;
  for (const objects::ObjectCategory c : objects::all_object_categories()) {
    all.emplace_back(objects::category_name(c));
  }
  return all;
}

std::vector<RobustnessSet> plan_robustness(const RobustnessOptions& options) {
  if (options.seeds < 0 || options.candidates < 0) {
    throw std::invalid_argument("--seeds and --candidates must not be negative");
  }
  if (!options.rigid && !options.soft) {
    throw std::invalid_argument("neither rigid nor soft objects asked for");
  }
  std::vector<std::string> grippers = options.grippers;
  if (grippers.empty()) {
    for (const GripperDefaults& d : kDefaults) grippers.emplace_back(d.name);
  }
  const std::vector<std::string> categories = robustness_categories(options.categories);
  for (const std::string& category : categories) objects::parse_object_category(category);
  std::vector<RobustnessSet> sets;
  for (const std::string& gripper : grippers) {
    const GripperDefaults& d = defaults_of(gripper);
    for (const std::string& category : categories) {
      for (const bool soft : {false, true}) {
        if (soft ? !options.soft : !options.rigid) continue;
        const int seeds = options.seeds > 0 ? options.seeds : soft ? d.soft_seeds : d.rigid_seeds;
        const int candidates = options.candidates > 0 ? options.candidates
                               : soft                 ? d.soft_candidates
                                                      : d.rigid_candidates;
        sets.push_back({gripper, category, soft, seeds, candidates, options.production_models,
                        options.soft_interior_growth, options.fine_fin_ray});
      }
    }
  }
  return sets;
}

RobustnessResult run_robustness(const RobustnessOptions& options) {
  RobustnessResult result;
  result.sets = plan_robustness(options);
  result.threads = options.threads > 0 ? options.threads : tbb::this_task_arena::max_concurrency();
  const auto start = std::chrono::steady_clock::now();
  CategoryRun run{result, options.parameters, options.full_trials, tbb::task_arena(result.threads)};
  // The rigid and soft sets of one gripper and category walk the seeds together, so that a
  // seed's candidates serve both.
  for (std::size_t i = 0; i < result.sets.size();) {
    std::size_t j = i + 1;
    while (j < result.sets.size() && result.sets[j].gripper == result.sets[i].gripper &&
           result.sets[j].category == result.sets[i].category) {
      ++j;
    }
    run.walk_seeds(i, j);
    i = j;
  }
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace grip::bench
