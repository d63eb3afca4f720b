#include "farm/trial_runner.hpp"

#include <array>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>

#include "src/trial/grasp_trial.hpp"
#include "src/trial/gripper_record.hpp"
#include "src/trial/hand_trial.hpp"
#include "src/trial/hand_trial_scene.hpp"
#include "src/trial/trial_scene.hpp"

namespace grip::farm {

namespace {

trial::HandTrialGrasp hand_grasp(const synth::HandGrasp& hand) {
  return {hand.pose, hand.joints, hand.contacts, hand.contact_normals};
}

trial::ParallelGrasp parallel_grasp(const synth::HandGrasp& hand) {
  return {hand.pose, hand.joints[0]};
}

// Every candidate's grasp: of its one hand, or of both (the first hand's first).
template <typename Grasp>
std::vector<Grasp> one_hand(const std::vector<const synth::Candidate*>& candidates,
                            Grasp (*convert)(const synth::HandGrasp&)) {
  std::vector<Grasp> grasps;
  for (const synth::Candidate* c : candidates) grasps.push_back(convert(c->hands.front()));
  return grasps;
}

template <typename Grasp>
std::vector<std::array<Grasp, 2>> two_hands(const std::vector<const synth::Candidate*>& candidates,
                                            Grasp (*convert)(const synth::HandGrasp&)) {
  std::vector<std::array<Grasp, 2>> grasps;
  for (const synth::Candidate* c : candidates) {
    grasps.push_back({convert(c->hands[0]), convert(c->hands[1])});
  }
  return grasps;
}

}  // namespace

struct TrialRunner::Scene {
  std::variant<std::unique_ptr<trial::TrialScene>, std::unique_ptr<trial::HandTrialScene>> scene;
};

TrialRunner::TrialRunner(const trial::TrialObject& object, grippers::GripperKind gripper,
                         bool bimanual, const trial::TrialParameters& parameters)
    : scene_(std::make_unique<Scene>()), bimanual_(bimanual) {
  const grippers::GripperType& type = grippers::gripper_type(gripper);
  if (type.is_hand()) {
    std::vector<grippers::HandModel> hands;
    hands.push_back(grippers::make_hand(gripper, grippers::HandSide::kRight));
    if (bimanual) hands.push_back(grippers::make_hand(gripper, grippers::HandSide::kLeft));
    scene_->scene = std::make_unique<trial::HandTrialScene>(object, std::move(hands),
                                                            std::string(type.name), parameters);
  } else {
    scene_->scene = std::make_unique<trial::TrialScene>(
        object, grippers::make_parallel_gripper(gripper), parameters, bimanual ? 2 : 1);
  }
}

TrialRunner::~TrialRunner() = default;

io::GripperRecord TrialRunner::gripper_record() const {
  return std::visit([](const auto& scene) { return trial::gripper_record(*scene); }, scene_->scene);
}

const solver::Model& TrialRunner::model() const {
  return *std::visit([](const auto& scene) { return scene->model(); }, scene_->scene);
}

std::vector<trial::TrialOutcome> TrialRunner::run(
    const std::vector<const synth::Candidate*>& candidates, const std::vector<std::uint64_t>& ids,
    int threads, bool trajectory, std::function<void(std::size_t)> after_step,
    std::shared_ptr<solver::LinearSystemSolver> big_system_solver) const {
  const std::size_t hands = bimanual_ ? 2 : 1;
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    if (candidates[k]->hands.size() != hands) {
      throw std::invalid_argument("candidate " + std::to_string(ids.at(k)) + " has " +
                                  std::to_string(candidates[k]->hands.size()) +
                                  " hand(s), but its gripper setting takes " +
                                  std::to_string(hands));
    }
  }
  trial::TrialRunOptions options;
  options.threads = threads;
  options.trajectory = trajectory;
  options.ids = ids;
  options.max_active = 2 * threads;  // enough to keep every thread busy while others freeze
  options.after_step = std::move(after_step);
  options.big_system_solver = std::move(big_system_solver);
  if (auto* parallel = std::get_if<std::unique_ptr<trial::TrialScene>>(&scene_->scene)) {
    if (bimanual_) {
      return trial::run_bimanual_trials(**parallel, two_hands(candidates, parallel_grasp), options);
    }
    return trial::run_trials(**parallel, one_hand(candidates, parallel_grasp), options);
  }
  const trial::HandTrialScene& hand =
      *std::get<std::unique_ptr<trial::HandTrialScene>>(scene_->scene);
  if (bimanual_) {
    return trial::run_bimanual_hand_trials(hand, two_hands(candidates, hand_grasp), options);
  }
  return trial::run_hand_trials(hand, one_hand(candidates, hand_grasp), options);
}

}  // namespace grip::farm
