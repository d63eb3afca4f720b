#include "src/trial/trial.hpp"

#include <stdexcept>
#include <string>
#include <utility>

#include "src/trial/hand_trial_scene.hpp"
#include "src/trial/parallel_trial_scene.hpp"

namespace grip::trial {

std::unique_ptr<TrialScene> make_trial_scene(const TrialObject& object,
                                             const grippers::GripperType& gripper, int count,
                                             const TrialParameters& parameters,
                                             const grippers::FinRayOptions& finger) {
  if (gripper.is_hand()) {
    // A bimanual hand trial's second hand is the left one (grip synth --bimanual).
    std::vector<grippers::HandModel> hands;
    hands.push_back(grippers::make_hand(gripper.kind, grippers::HandSide::kRight));
    if (count == 2) hands.push_back(grippers::make_hand(gripper.kind, grippers::HandSide::kLeft));
    return std::make_unique<HandTrialScene>(object, std::move(hands), std::string(gripper.name),
                                            parameters);
  }
  // Named as users type it, as a hand is: the dataset's record takes the scene's name.
  grippers::ParallelGripper parallel = gripper.make_parallel(finger);
  parallel.name = std::string(gripper.name);
  return std::make_unique<ParallelTrialScene>(object, parallel, parameters, count);
}

std::vector<TrialOutcome> run_trials(const TrialScene& scene,
                                     const std::vector<synth::Candidate>& candidates,
                                     const TrialRunOptions& options) {
  const auto hands = static_cast<std::size_t>(scene.gripper_count());
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    if (candidates[k].hands.size() != hands) {
      const std::uint64_t id = options.ids.size() > k ? options.ids[k] : k;
      throw std::invalid_argument("candidate " + std::to_string(id) + " has " +
                                  std::to_string(candidates[k].hands.size()) +
                                  " hand(s), but its trial scene takes " + std::to_string(hands));
    }
  }
  return run_protocol(*scene.protocol_gripper(candidates), options);
}

}  // namespace grip::trial
