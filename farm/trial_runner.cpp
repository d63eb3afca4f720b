#include "farm/trial_runner.hpp"

#include <string>
#include <utility>
#include <variant>

#include "src/trial/grasp_trial.hpp"
#include "src/trial/gripper_record.hpp"
#include "src/trial/hand_trial.hpp"
#include "src/trial/hand_trial_scene.hpp"
#include "src/trial/trial_scene.hpp"

namespace grip::farm {

struct TrialRunner::Scene {
  std::variant<std::unique_ptr<trial::TrialScene>, std::unique_ptr<trial::HandTrialScene>> scene;
};

TrialRunner::TrialRunner(const trial::TrialObject& object, grippers::GripperKind gripper,
                         const trial::TrialParameters& parameters)
    : scene_(std::make_unique<Scene>()) {
  const grippers::GripperType& type = grippers::gripper_type(gripper);
  if (type.is_hand()) {
    scene_->scene = std::make_unique<trial::HandTrialScene>(
        object, grippers::make_hand(gripper, grippers::HandSide::kRight), std::string(type.name),
        parameters);
  } else {
    scene_->scene = std::make_unique<trial::TrialScene>(
        object, grippers::make_parallel_gripper(gripper), parameters);
  }
}

TrialRunner::~TrialRunner() = default;

io::GripperRecord TrialRunner::gripper_record() const {
  return std::visit([](const auto& scene) { return trial::gripper_record(*scene); }, scene_->scene);
}

std::vector<trial::TrialOutcome> TrialRunner::run(
    const std::vector<const synth::Candidate*>& candidates, const std::vector<std::uint64_t>& ids,
    int threads, bool trajectory, std::function<void(std::size_t)> after_step) const {
  trial::TrialRunOptions options;
  options.threads = threads;
  options.trajectory = trajectory;
  options.ids = ids;
  options.max_active = 2 * threads;  // enough to keep every thread busy while others freeze
  options.after_step = std::move(after_step);
  if (auto* parallel = std::get_if<std::unique_ptr<trial::TrialScene>>(&scene_->scene)) {
    std::vector<trial::ParallelGrasp> grasps;
    for (const synth::Candidate* c : candidates) {
      grasps.push_back({c->hands.front().pose, c->hands.front().joints[0]});
    }
    return trial::run_trials(**parallel, grasps, options);
  }
  std::vector<trial::HandTrialGrasp> grasps;
  for (const synth::Candidate* c : candidates) {
    const synth::HandGrasp& hand = c->hands.front();
    grasps.push_back({hand.pose, hand.joints, hand.contacts, hand.contact_normals});
  }
  return trial::run_hand_trials(*std::get<std::unique_ptr<trial::HandTrialScene>>(scene_->scene),
                                grasps, options);
}

}  // namespace grip::farm
