#pragma once
// The dexterous grasp optimizer for the 16-DoF hand in the spirit of DexGraspNet: each attempt
// starts the hand on the object's inflated convex hull (in a random direction from its centre),
// anneals the energy of hand_energy.hpp with RMSProp-scaled gradient steps, contact resampling and
// Metropolis acceptance, then runs the clearance fix and the exact checks. Attempts run in
// parallel, one seed each.
#include <cstdint>

#include "src/synth/attempt_driver.hpp"
#include "src/synth/hand_clearance_fix.hpp"
#include "src/synth/hand_energy.hpp"

namespace grip::synth {

struct HandOptimizerParams {
  int steps = 1500;          // annealing steps per attempt
  int contacts = 4;          // contact candidates taking part in the energy
  double step_size = 0.005;  // RMSProp step (m or rad per unit of scaled gradient)
  double rms_decay = 0.98;   // decay of RMSProp's squared-gradient average
  double starting_temperature = 18.0;
  // Temperature and step size decay by this factor `annealing_periods` times over an attempt's
  // steps (DexGraspNet's schedule: 0.95 every 30 of its 6000 steps), so the attempt ends cold
  // whatever its step count: at 1500 steps and a fixed period of 30 it ended at 1.4, hot enough
  // to undo the force closure it had found.
  double temperature_decay = 0.95;
  int annealing_periods = 200;
  double switch_probability = 0.5;  // per step, per contact: draw another candidate
  double hull_distance_min = 0.01;  // m, the hull inflation the palm starts at
  double hull_distance_max = 0.03;
  double approach_jitter = 0.26;  // rad, palm normal's deviation from the hull normal
  double joint_jitter = 0.1;      // rad, standard deviation of the initial joints
  int penetration_points = 1000;  // object samples for E_pen
  HandEnergyWeights weights;
  ClearanceFixParams clearance;
  // An attempt whose grasp, after the clearance fix, has a force-closure error E_fc above this
  // is rejected: four unit normals pointing one way give 4, and such a grasp is pushed out of
  // the hand or dropped (docs/synthesis.md).
  double max_force_closure_error = 0.5;
  std::int64_t max_attempts_per_candidate = 20;
  int block = 16;  // attempts per parallel block
};

// Energy terms of a hand candidate (Candidate::energies, in this order): fc, dis, pen, spen,
// joints, normal, total (HandEnergyTerms) of the grasp returned, after the clearance fix.
// Every returned candidate has exact clearance >= d_hat + margin and no intersection between
// non-adjacent links.
SynthesisResult optimize_hand_grasps(const PreparedObject& object, const PreparedHand& hand,
                                     const HandOptimizerParams& params, std::uint64_t seed,
                                     int count);

// The hand point placed on the inflated hull at initialization (palm face, near the fingers).
inline const Eigen::Vector3d kPalmGraspPoint{0.07, 0.0, 0.0};

}  // namespace grip::synth
