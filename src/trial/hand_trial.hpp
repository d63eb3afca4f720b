#pragma once
// The grasp trial protocol for a dexterous hand (GRIP, Sec. III-D), run for many candidates of
// one object and hand as one solver::Batch: gravity off, each finger closes through its joints
// on the held object until its contact force is the grip force or its joints reach their
// limits, the released grasp settles, then gravity along +x, -x, +y, -y, +z, -z (world) for one
// phase each (run_protocol). Outcomes as
// run_trials gives them for parallel grippers, with one closing force per finger and the
// hand's joint values per frame. A bimanual trial runs a right and a left hand of one scene the
// same way, their fingers together.
#include <array>
#include <vector>

#include "src/trial/hand_trial_scene.hpp"
#include "src/trial/trial_outcome.hpp"
#include "src/trial/trial_protocol.hpp"

namespace grip::trial {

// One outcome per grasp, in order. Each record's wall_time is the batch's wall time divided
// by the number of candidates. Throws std::out_of_range naming a candidate whose joints the
// hand cannot take.
std::vector<TrialOutcome> run_hand_trials(const HandTrialScene& scene,
                                          const std::vector<HandTrialGrasp>& grasps,
                                          const TrialRunOptions& options = {});

// The same for a scene of two hands: grasps[k] is candidate k's grasp per hand (the right hand,
// then the left); fingers, closing forces and the frames' poses and joints follow that order.
// Throws std::invalid_argument for a scene of one hand (and run_hand_trials for one of two).
std::vector<TrialOutcome> run_bimanual_hand_trials(
    const HandTrialScene& scene, const std::vector<std::array<HandTrialGrasp, 2>>& grasps,
    const TrialRunOptions& options = {});

}  // namespace grip::trial
