#pragma once
// The LEAP-style hand with each link's mesh replaced by a coarse capsule, for tests and
// benchmarks where a hand trial step must cost a fraction of the full hand's.
#include "src/grippers/hand_model.hpp"
#include "src/grippers/leap_hand.hpp"

namespace grip::grippers {

// The hand of write_leap_hand (same URDF, joints and hand points) whose link meshes are
// 8-sided capsules inscribed in the full ones, so clearances synthesized on it only grow on
// the full hand. Writes and removes a scratch folder of its own (one per process).
HandModel coarse_leap_hand(HandSide side = HandSide::kRight);

}  // namespace grip::grippers
