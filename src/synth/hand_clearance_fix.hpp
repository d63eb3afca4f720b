#pragma once
// The clearance fix after hand optimization: inverse kinematics moves the links that come
// within d_hat + margin of the object along the object's surface normal until every link keeps
// that distance (the palm, which no joint moves, moves the whole hand).
#include <optional>

#include "src/synth/hand_energy.hpp"

namespace grip::synth {

struct ClearanceFixParams {
  double d_hat = 1e-3;    // m, the IPC barrier's activation distance
  double margin = 5e-4;   // m, kept beyond d_hat
  int iterations = 40;    // link moves before giving up
  double damping = 1e-3;  // m, damped least squares: dq = J^T (J J^T + damping^2 I)^-1 dx
};

struct FixedHand {
  HandState state;
  double min_distance = 0.0;  // m, exact hand-object clearance after the fix (capped at 4 d_hat)
};

// Returns the moved state once every link has exact clearance >= d_hat + margin, or nothing if
// `iterations` moves did not get there.
std::optional<FixedHand> fix_hand_clearance(const PreparedHand& hand, const PreparedObject& object,
                                            HandState state, const ClearanceFixParams& params);

}  // namespace grip::synth
