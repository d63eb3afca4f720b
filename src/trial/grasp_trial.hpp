#pragma once
// The grasp trial protocol for parallel grippers (GRIP, Sec. III-D), run for many candidates
// of one object and gripper as one solver::Batch: gravity off, the jaws close until each
// finger's contact force exceeds the stop force, the grasp settles, then gravity along +x, -x,
// +y, -y, +z, -z (world) for one phase each; the verdict, D1/D2, closing forces, stress and
// the recorded frames make each candidate's io::CandidateResult.
#include <cstdint>
#include <vector>

#include "src/trial/trial_outcome.hpp"
#include "src/trial/trial_scene.hpp"

namespace grip::trial {

struct TrialRunOptions {
  int threads = 0;           // the batch's threads; 0: all cores. Results do not depend on it.
  bool trajectory = true;    // fill CandidateResult::trajectory
  bool body_frames = false;  // fill TrialOutcome::body_frames (all bodies, stress; for VTK)
  std::vector<std::uint64_t> ids;  // record ids per candidate; empty: 0, 1, 2, ...
};

// One outcome per grasp, in order. Each record's wall_time is the batch's wall time divided
// by the number of candidates (a batch does not time its environments one by one). Throws
// std::out_of_range naming the candidate whose opening the gripper cannot take.
std::vector<TrialOutcome> run_trials(const TrialScene& scene,
                                     const std::vector<ParallelGrasp>& grasps,
                                     const TrialRunOptions& options = {});

}  // namespace grip::trial
