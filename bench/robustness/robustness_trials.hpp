#pragma once
// The trials as `grip bench robustness` runs them, shared by the benchmarks built on it: the
// candidates as `grip synth` makes them, the object rigid or coarsely meshed, the coarse grippers
// (robustness_gripper_model), and a scene built once for any number of runs.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "bench/robustness/robustness_benchmark.hpp"
#include "src/grippers/parallel_gripper.hpp"
#include "src/synth/candidate.hpp"
#include "src/trial/trial_object.hpp"
#include "src/trial/trial_outcome.hpp"
#include "src/trial/trial_parameters.hpp"

namespace grip::trial {
class TrialScene;
}  // namespace grip::trial

namespace grip::bench {

// The object model of rigid or soft objects here, in words.
std::string robustness_object_model(bool soft, bool production_models,
                                    double interior_growth = geometry::kSoftObjectInteriorGrowth);

// Candidates on the shape of the set's category and `seed`, `count` asked (fewer when synthesis
// finds fewer), as `grip synth --seed` makes them.
std::vector<synth::Candidate> synthesize_candidates(const RobustnessSet& set, std::uint64_t seed,
                                                    int count);

// The shape of the set's category and `seed` with `grip trial --soft`'s material; a soft one
// meshed as robustness_object_model says.
trial::TrialObject make_object(const RobustnessSet& set, std::uint64_t seed);

// The parallel gripper (rigid jaws or a fin-ray of the set's model) a set of a parallel gripper
// simulates, built once.
const grippers::ParallelGripper& robustness_parallel_gripper(const RobustnessSet& set);

// One object and the set's gripper: the trial scene, built once, run for any candidates.
class RobustnessScene {
 public:
  // Throws std::invalid_argument (naming the object) for an unusable object.
  RobustnessScene(const RobustnessSet& set, const trial::TrialObject& object,
                  const trial::TrialParameters& parameters);
  ~RobustnessScene();
  RobustnessScene(const RobustnessScene&) = delete;
  RobustnessScene& operator=(const RobustnessScene&) = delete;

  // The candidates' trials as one solver::Batch on `threads` threads (0: all cores), without
  // trajectories; with full_trials, decided trials run to the end (trial::TrialRunOptions).
  // Throws std::out_of_range for a candidate the gripper cannot take.
  std::vector<trial::TrialOutcome> run(const std::vector<synth::Candidate>& candidates, int threads,
                                       bool full_trials = false) const;
  const trial::TrialParameters& parameters() const;

 private:
  std::unique_ptr<trial::TrialScene> scene_;  // rigid jaws, fin-ray or leap
};

// Candidate k of the set's shape of `seed`, as its trial under `parameters` ended.
RobustnessTrial robustness_trial(const RobustnessSet& set, std::uint64_t seed, std::uint64_t k,
                                 const trial::TrialOutcome& outcome,
                                 const trial::TrialParameters& parameters);

}  // namespace grip::bench
