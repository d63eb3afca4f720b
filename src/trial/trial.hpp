#pragma once
// The grasp trial's one entry (GRIP, Sec. III-D): a trial scene built from a gripper's registry
// row (a parallel gripper or a hand, one or two), and run_trials, which runs candidates through
// the protocol as one batch of an engine (solver::Engine): gravity off, the fingers close on the
// held object until each finger's contact force is the grip force (or its path ends), the
// released grasp settles, then gravity along +x, -x, +y, -y, +z, -z (world) for one phase each;
// the verdict, D1/D2, closing forces, stress and the recorded frames make each candidate's
// io::CandidateResult.
#include <memory>
#include <vector>

#include "src/grippers/gripper_registry.hpp"
#include "src/synth/candidate.hpp"
#include "src/trial/trial_object.hpp"
#include "src/trial/trial_outcome.hpp"
#include "src/trial/trial_parameters.hpp"
#include "src/trial/trial_protocol.hpp"
#include "src/trial/trial_scene.hpp"

namespace grip::trial {

// The scene of the registry row's gripper: `count` of them (1, or 2 for a bimanual trial: two
// parallel grippers, or a right and a left hand), a meshed finger meshed as `finger` says, named
// as the row names it (the dataset's gripper record: "fin-ray", "leap-bimanual").
// Throws std::invalid_argument (naming the object) for an unusable object or parameters.
std::unique_ptr<TrialScene> make_trial_scene(const TrialObject& object,
                                             const grippers::GripperType& gripper, int count,
                                             const TrialParameters& parameters,
                                             const grippers::FinRayOptions& finger = {});

// One outcome per candidate, in order; each record's wall_time is the batch's wall time divided
// by the number of candidates (a batch does not time its environments one by one). Throws
// std::invalid_argument for a candidate with another number of hands than the scene's grippers
// (or options.ids not one per candidate), std::out_of_range naming a candidate the gripper
// cannot take.
std::vector<TrialOutcome> run_trials(const TrialScene& scene,
                                     const std::vector<synth::Candidate>& candidates,
                                     const TrialRunOptions& options = {});

}  // namespace grip::trial
