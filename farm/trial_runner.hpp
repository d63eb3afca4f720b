#pragma once
// One object's trials with one gripper of the job, whichever kind: the trial scene (its solver
// Model, shared by every environment) built once, then work units of candidates run through it.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "io/gripper_record.hpp"
#include "src/grippers/gripper_registry.hpp"
#include "src/synth/candidate.hpp"
#include "src/trial/trial_object.hpp"
#include "src/trial/trial_outcome.hpp"
#include "src/trial/trial_parameters.hpp"

namespace grip::farm {

class TrialRunner {
 public:
  TrialRunner(const trial::TrialObject& object, grippers::GripperKind gripper,
              const trial::TrialParameters& parameters);
  ~TrialRunner();
  TrialRunner(const TrialRunner&) = delete;
  TrialRunner& operator=(const TrialRunner&) = delete;

  io::GripperRecord gripper_record() const;

  // The candidates' trials as one solver::Batch on `threads` threads; outcome k carries ids[k].
  // after_step: trial::TrialRunOptions' (may be empty).
  std::vector<trial::TrialOutcome> run(const std::vector<const synth::Candidate*>& candidates,
                                       const std::vector<std::uint64_t>& ids, int threads,
                                       bool trajectory,
                                       std::function<void(std::size_t)> after_step = {}) const;

 private:
  struct Scene;
  std::unique_ptr<Scene> scene_;
};

}  // namespace grip::farm
