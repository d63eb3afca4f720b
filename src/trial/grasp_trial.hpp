#pragma once
// The grasp trial protocol for parallel grippers (GRIP, Sec. III-D), run for many candidates
// of one object and gripper as one solver::Batch: gravity off, the jaws close on the held object
// until each finger's contact force is the grip force, the released grasp settles, then gravity
// along +x, -x, +y, -y, +z, -z (world) for one phase each (run_protocol); the verdict, D1/D2,
// closing forces, stress and the recorded frames make each candidate's io::CandidateResult.
// A bimanual trial runs two grippers of one scene the same way, their four fingers together.
#include <array>
#include <vector>

#include "src/trial/trial_outcome.hpp"
#include "src/trial/trial_protocol.hpp"
#include "src/trial/trial_scene.hpp"

namespace grip::trial {

// One outcome per grasp, in order. Each record's wall_time is the batch's wall time divided
// by the number of candidates (a batch does not time its environments one by one). Throws
// std::out_of_range naming the candidate whose opening the gripper cannot take.
std::vector<TrialOutcome> run_trials(const TrialScene& scene,
                                     const std::vector<ParallelGrasp>& grasps,
                                     const TrialRunOptions& options = {});

// The same for a scene of two grippers: grasps[k] is candidate k's grasp per gripper (the first
// gripper's first); fingers, closing forces and the frames' poses and joints follow that order.
// Throws std::invalid_argument for a scene of one gripper (and run_trials for one of two).
std::vector<TrialOutcome> run_bimanual_trials(
    const TrialScene& scene, const std::vector<std::array<ParallelGrasp, 2>>& grasps,
    const TrialRunOptions& options = {});

}  // namespace grip::trial
