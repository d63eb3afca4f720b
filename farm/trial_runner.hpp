#pragma once
// One object's trials with one gripper setting of the job, whichever kind, one gripper or two
// (bimanual): the trial scene (its solver Model, shared by every environment) built once, then
// work units of candidates run through it.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "io/gripper_record.hpp"
#include "solver/linear/linear_system_solver.hpp"
#include "solver/model/model.hpp"
#include "src/grippers/gripper_registry.hpp"
#include "src/synth/candidate.hpp"
#include "src/trial/trial_object.hpp"
#include "src/trial/trial_outcome.hpp"
#include "src/trial/trial_parameters.hpp"

namespace grip::farm {

class TrialRunner {
 public:
  // bimanual: two grippers of the kind (two parallel grippers, or a right and a left hand), run
  // from candidates with two hands (the second hand is the left one).
  TrialRunner(const trial::TrialObject& object, grippers::GripperKind gripper, bool bimanual,
              const trial::TrialParameters& parameters);
  ~TrialRunner();
  TrialRunner(const TrialRunner&) = delete;
  TrialRunner& operator=(const TrialRunner&) = delete;

  io::GripperRecord gripper_record() const;
  // The trial scene's solver model, shared by every environment of its trials.
  const solver::Model& model() const;

  // The candidates' trials as one solver::Batch on `threads` threads; outcome k carries ids[k].
  // Throws std::invalid_argument for a candidate with other than the runner's number of hands.
  // after_step and big_system_solver: trial::TrialRunOptions' (may be empty).
  std::vector<trial::TrialOutcome> run(
      const std::vector<const synth::Candidate*>& candidates, const std::vector<std::uint64_t>& ids,
      int threads, bool trajectory, std::function<void(std::size_t)> after_step = {},
      std::shared_ptr<solver::LinearSystemSolver> big_system_solver = nullptr) const;

 private:
  struct Scene;
  std::unique_ptr<Scene> scene_;
  bool bimanual_ = false;
};

}  // namespace grip::farm
