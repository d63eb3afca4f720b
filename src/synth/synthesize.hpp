#pragma once
// One entry point for every gripper: unimanual candidates from the antipodal sampler
// (fin-ray, parallel-jaw) or the hand optimizer (leap), and bimanual ones composed from a
// right and a left pool of them.
#include <cstdint>

#include "src/grippers/fin_ray_finger.hpp"
#include "src/synth/antipodal_sampler.hpp"
#include "src/synth/bimanual.hpp"
#include "src/synth/hand_optimizer.hpp"

namespace grip::synth {

struct SynthesisParams {
  AntipodalParams antipodal;
  HandOptimizerParams hand;
  BimanualParams bimanual;
  // Bimanual: each side's pool holds pool_factor * sqrt(count / r1) unimanual candidates, so
  // that the selected cluster pairs hold about pool_factor^2 * count combinations.
  double pool_factor = 1.5;
};

// `count` candidates (fewer if the attempt limits are reached; the result says how many
// attempts it took). Same object, gripper, parameters and seed give the same candidates
// whatever the thread count. The gripper is built here from its type (a hand from its shipped
// assets, a described gripper from its file; the fin-ray with `finger`'s shape).
SynthesisResult synthesize(const PreparedObject& object, const grippers::GripperType& gripper,
                           bool bimanual, const SynthesisParams& params, std::uint64_t seed,
                           int count, const grippers::FinRayOptions& finger = {});

}  // namespace grip::synth
