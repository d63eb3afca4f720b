#include "src/synth/synthesize.hpp"

#include <chrono>
#include <cmath>
#include <optional>

#include "src/grippers/gripper_registry.hpp"
#include "src/synth/prepared_hand.hpp"

namespace grip::synth {
namespace {

void add(SynthesisResult& total, const SynthesisResult& part) {
  total.attempts += part.attempts;
  total.accepted += part.accepted;
  for (const auto& [reason, n] : part.rejections) total.rejections[reason] += n;
}

}  // namespace

SynthesisResult synthesize(const PreparedObject& object, const grippers::GripperType& gripper,
                           bool bimanual, const SynthesisParams& params, std::uint64_t seed,
                           int count, const grippers::FinRayOptions& finger) {
  const auto start = std::chrono::steady_clock::now();
  const bool is_hand = gripper.is_hand();
  const auto prepared_hand = [&](grippers::HandSide side) {
    return PreparedHand(grippers::make_hand(gripper.kind, side));
  };
  std::optional<grippers::ParallelGripper> jaws;
  if (!is_hand) jaws = gripper.make_parallel(finger);
  const auto unimanual = [&](const PreparedHand* hand, std::uint64_t s, int n) {
    return hand ? optimize_hand_grasps(object, *hand, params.hand, s, n)
                : sample_antipodal_grasps(object, *jaws, gripper.kind, params.antipodal, s, n);
  };
  SynthesisResult result;
  if (!bimanual) {
    const std::optional<PreparedHand> right =
        is_hand ? std::optional(prepared_hand(grippers::HandSide::kRight)) : std::nullopt;
    result = unimanual(right ? &*right : nullptr, seed, count);
  } else {
    std::optional<PreparedHand> right, left;
    if (is_hand) {
      right.emplace(prepared_hand(grippers::HandSide::kRight));
      left.emplace(prepared_hand(grippers::HandSide::kLeft));
    }
    const int pool = static_cast<int>(
        std::ceil(params.pool_factor * std::sqrt(count / params.bimanual.pair_fraction)));
    const SynthesisResult right_pool = unimanual(right ? &*right : nullptr, 2 * seed, pool);
    const SynthesisResult left_pool = unimanual(left ? &*left : nullptr, 2 * seed + 1, pool);
    add(result, right_pool);
    add(result, left_pool);
    const auto posed = [&](const Candidate& c, bool is_left) {
      if (jaws) return posed_parallel_surface(*jaws, c.hands[0]);
      const PreparedHand& hand = is_left ? *left : *right;
      return hand.kinematics().posed_surface(
          hand.kinematics().link_poses(c.hands[0].pose, c.hands[0].joints));
    };
    BimanualStatistics statistics;
    result.candidates = compose_bimanual(object, right_pool.candidates, left_pool.candidates, count,
                                         params.bimanual, seed, posed, &statistics);
    result.rejections["bimanual: hands too close"] += statistics.colliding;
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace grip::synth
