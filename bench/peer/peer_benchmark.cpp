#include "bench/peer/peer_benchmark.hpp"

#include <spdlog/spdlog.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "bench/common/cpu_clock.hpp"
#include "bench/peer/grasp_distances.hpp"
#include "bench/peer/mujoco_hand_trial.hpp"
#include "bench/peer/mujoco_trial.hpp"
#include "bench/peer/peer_vtk.hpp"
#include "bench/robustness/robustness_trials.hpp"
#include "src/grippers/coarse_leap_hand.hpp"
#include "src/objects/object_library.hpp"
#include "src/trial/hand_trial_scene.hpp"
#include "src/trial/trial.hpp"

namespace grip::bench {
namespace {

std::string verdict_text(const io::CandidateRecord& record) {
  return record.failure == io::FailureKind::kNone ? "success"
                                                  : std::string(io::to_string(record.failure));
}

std::vector<std::string> categories_of(const PeerOptions& options) {
  return options.categories.empty() ? kPeerCategories : options.categories;
}

// A row's grip half: candidate k of the shape, its verdict, D1/D2 and largest slip, and the
// thread's CPU seconds `grip_cpu_seconds`.
PeerTrial grip_row(const RobustnessSet& set, std::uint64_t seed, std::size_t k,
                   const trial::TrialOutcome& outcome, const trial::TrialParameters& parameters,
                   double grip_cpu_seconds) {
  PeerTrial t;
  t.gripper = set.gripper;
  t.category = set.category;
  t.seed = seed;
  t.candidate = k;
  t.grip_cpu_seconds = grip_cpu_seconds;
  const io::CandidateRecord& record = outcome.result.record;
  t.grip_verdict = verdict_text(record);
  t.grip_d1 = record.d1;
  t.grip_d2 = record.d2;
  t.grip_slip = robustness_trial(set, seed, k, outcome, parameters).largest_slip;
  return t;
}

// A row's MuJoCo half (a jaws' or a hand's outcome): its verdict, and where it settled, D1/D2
// from `settled_distances()` and its largest slip.
template <typename Outcome, typename SettledDistances>
void add_mujoco(const Outcome& m, SettledDistances&& settled_distances, PeerTrial& t) {
  t.mujoco_verdict = m.verdict;
  t.mujoco_message = m.message;
  if (m.settled) {
    const metrics::DistanceMetrics d = settled_distances();
    t.mujoco_d1 = d.d1;
    t.mujoco_d2 = d.d2;
    t.mujoco_slip = m.largest_slip;
  }
  t.mujoco_cpu_seconds = m.cpu_seconds;
  t.mujoco_compile_cpu_seconds = m.compile_cpu_seconds;
}

// The first candidate of each kind of disagreement, once per run: the VTK stem to write it
// under ("grip_holds_..." or "mujoco_holds_..."), or empty.
std::string disagreement_stem(const PeerOptions& options, const PeerResult& result,
                              const RobustnessSet& set, std::uint64_t seed, std::size_t k,
                              const PeerTrial& t) {
  const bool grip_held = t.grip_verdict == "success", mujoco_held = t.mujoco_verdict == "success";
  const std::string kind = mujoco_held ? "mujoco_holds" : "grip_holds";
  const auto written = [&](const std::string& v) { return v.rfind(kind, 0) == 0; };
  if (options.vtk.empty() || grip_held == mujoco_held || refused_by_grip(t) ||
      std::any_of(result.vtk.begin(), result.vtk.end(), written)) {
    return "";
  }
  return fmt::format("{}_{}_{}_seed{}_candidate{}", kind, set.gripper, set.category, seed, k);
}

// One shape with a parallel gripper (rigid jaws or fin-ray): grip's trials, then MuJoCo's,
// candidate by candidate. The first candidate of each kind of disagreement is written as VTK if
// options.vtk is set.
void run_jaws_shape(const RobustnessSet& set, std::uint64_t seed,
                    const std::vector<synth::Candidate>& candidates, const PeerOptions& options,
                    PeerResult& result) {
  // The gripper RobustnessScene simulates, and the object as it prepares it.
  const grippers::ParallelGripper& jaws = robustness_parallel_gripper(set);
  const trial::TrialObject object = make_object(set, seed);
  const RobustnessScene scene(set, object, options.parameters);
  const GraspDistances distances(jaws, object.surface, options.parameters);
  // The fin-ray's pads set their own friction; rigid jaws combine theirs with the object's
  // (trial::ParallelTrialScene).
  const double friction =
      jaws.soft_finger
          ? jaws.soft_finger->material.friction
          : std::sqrt(object.material.friction * options.parameters.rigid_finger_friction);
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    const double start = process_cpu_seconds();
    const trial::TrialOutcome outcome = scene.run({candidates[k]}, options.threads).front();
    PeerTrial t =
        grip_row(set, seed, k, outcome, options.parameters, process_cpu_seconds() - start);

    const synth::HandGrasp& hand = candidates[k].hands.front();
    MujocoSettings settings;
    settings.ipc = options.mujoco_ipc;
    const MujocoOutcome m =
        run_mujoco_trial(object.surface, object.material.density, friction, jaws, hand.pose,
                         hand.joints[0], options.parameters, settings);
    add_mujoco(
        m,
        [&] {
          return jaws.soft_finger ? distances(m.finger_vertices, m.object)
                                  : distances(m.fingers, m.object);
        },
        t);
    t.mujoco_penetration = m.deepest_penetration;
    t.mujoco_inverted_tets = m.most_inverted_tets;
    const std::string stem = disagreement_stem(options, result, set, seed, k, t);
    if (!stem.empty()) {
      write_peer_jaws_vtk(options.vtk, stem, object, jaws, hand, m, options.parameters,
                          options.threads);
      result.vtk.push_back(fmt::format("{}: grip {}, MuJoCo {}", stem, t.grip_verdict, m.verdict));
    }
    result.trials.push_back(std::move(t));
  }
}

// One shape with the hand, as run_jaws_shape: the hand RobustnessScene simulates (its coarse
// links), built here since MuJoCo's scene and D1/D2 take its links. The first candidate of each
// kind of disagreement is written as VTK if options.vtk is set.
void run_hand_shape(const RobustnessSet& set, std::uint64_t seed,
                    const std::vector<synth::Candidate>& candidates, const PeerOptions& options,
                    PeerResult& result) {
  static const grippers::HandModel hand = grippers::coarse_leap_hand();
  const trial::TrialObject object = make_object(set, seed);
  const trial::HandTrialScene scene(object, hand, set.gripper, options.parameters);
  const GraspDistances distances(scene, object.surface, options.parameters);
  const double friction =
      std::sqrt(object.material.friction * options.parameters.rigid_finger_friction);
  trial::TrialRunOptions run;
  run.threads = options.threads;
  run.trajectory = false;
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    const trial::HandTrialGrasp& grasp = candidates[k].hands.front();
    const double start = process_cpu_seconds();
    const trial::TrialOutcome outcome = trial::run_trials(scene, {candidates[k]}, run).front();
    PeerTrial t =
        grip_row(set, seed, k, outcome, options.parameters, process_cpu_seconds() - start);

    const MujocoHandOutcome m = run_mujoco_hand_trial(object.surface, object.material.density,
                                                      friction, scene, grasp, options.parameters);
    add_mujoco(
        m, [&] { return distances(m.links, m.object); }, t);
    t.mujoco_penetration = m.deepest_penetration;
    const std::string stem = disagreement_stem(options, result, set, seed, k, t);
    if (!stem.empty()) {
      write_peer_hand_vtk(options.vtk, stem, object, scene, grasp, m, options.threads);
      result.vtk.push_back(fmt::format("{}: grip {}, MuJoCo {}", stem, t.grip_verdict, m.verdict));
    }
    result.trials.push_back(std::move(t));
  }
}

}  // namespace

bool refused_by_grip(const PeerTrial& trial) {
  return trial.grip_verdict == io::to_string(io::FailureKind::kInitialPenetration);
}

void check_peer_options(const PeerOptions& options) {
  if (options.seeds < 1 || options.candidates < 1) {
    throw std::invalid_argument("grip bench peer: --seeds and --candidates must be at least 1");
  }
  if (std::find(kPeerGrippers.begin(), kPeerGrippers.end(), options.gripper) ==
      kPeerGrippers.end()) {
    throw std::invalid_argument("grip bench peer: unknown gripper '" + options.gripper +
                                "' (parallel-jaw, fin-ray or leap)");
  }
  if (options.mujoco_ipc && options.gripper != "fin-ray") {
    throw std::invalid_argument(
        "grip bench peer: --mujoco-ipc applies to --gripper fin-ray only (MuJoCo's IPC mode "
        "is for flexes, under its discrete integrator)");
  }
  try {
    for (const std::string& c : categories_of(options)) objects::parse_object_category(c);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("grip bench peer: ") + e.what());
  }
}

PeerResult run_peer(const PeerOptions& options) {
  check_peer_options(options);
  PeerResult result;
  result.gripper = options.gripper;
  result.mujoco_version = mujoco_version();
  result.mujoco_ipc = options.mujoco_ipc;
  result.parameters = options.parameters;
  result.threads = options.threads > 0 ? options.threads : tbb::this_task_arena::max_concurrency();
  tbb::task_arena arena(result.threads);
  const auto start = std::chrono::steady_clock::now();
  for (const std::string& category : categories_of(options)) {
    // The fin-ray is compared at its production mesh (RobustnessSet::production_models).
    const RobustnessSet set{options.gripper, category,           false,
                            options.seeds,   options.candidates, options.gripper == "fin-ray"};
    int found = 0;
    const auto last_seed = static_cast<std::uint64_t>(kSeedsTriedPerShape * options.seeds);
    for (std::uint64_t seed = 1; seed <= last_seed && found < options.seeds; ++seed) {
      const std::string shape = category + " seed " + std::to_string(seed);
      std::vector<synth::Candidate> candidates;
      arena.execute([&] { candidates = synthesize_candidates(set, seed, options.candidates); });
      if (candidates.empty()) {
        result.skipped.push_back(shape);
        continue;
      }
      ++found;
      if (static_cast<int>(candidates.size()) < options.candidates) {
        result.shortfalls.push_back(shape + ": " + std::to_string(candidates.size()) + " of " +
                                    std::to_string(options.candidates) + " candidates");
      }
      const auto begin = std::chrono::steady_clock::now();
      try {
        arena.execute([&] {
          if (options.gripper == "leap") {
            run_hand_shape(set, seed, candidates, options, result);
          } else {
            run_jaws_shape(set, seed, candidates, options, result);
          }
        });
      } catch (const std::exception& e) {
        result.shortfalls.push_back(shape + ": no trials (" + e.what() + ")");
        spdlog::warn("peer: {}", result.shortfalls.back());
        continue;
      }
      spdlog::info("peer: {} x {}: {} candidate(s) in {:.1f} s", options.gripper, shape,
                   candidates.size(),
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count());
    }
    if (found < options.seeds) {
      result.shortfalls.push_back(category + ": " + std::to_string(found) + " of " +
                                  std::to_string(options.seeds) + " shapes in seeds 1-" +
                                  std::to_string(last_seed));
    }
  }
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace grip::bench
