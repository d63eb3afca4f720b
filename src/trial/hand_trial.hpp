#pragma once
// The grasp trial protocol for a dexterous hand (GRIP, Sec. III-D), run for many candidates of
// one object and hand as one solver::Batch: gravity off, each finger closes through its joints
// on the held object until its contact force is the grip force or its joints reach their
// limits, the released grasp settles, then gravity along +x, -x, +y, -y, +z, -z (world) for one
// phase each (run_protocol). Outcomes as
// run_trials gives them for parallel grippers, with one closing force per finger and the
// hand's joint values per frame.
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

}  // namespace grip::trial
