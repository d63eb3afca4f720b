#pragma once
// How far one run of a scene's trials lies from a reference run of the same candidates: the
// object's pose in the gripper frame, its slip, every vertex, at times the protocol fixes
// (the settled grasp and the end of each gravity phase), and whether the verdicts agree.
#include <vector>

#include "io/candidate_record.hpp"
#include "src/trial/trial_outcome.hpp"
#include "src/trial/trial_parameters.hpp"

namespace grip::bench {

// One candidate's error against its reference. NaN where the two cannot be compared (no
// trajectory, or meshes of different sizes for the vertices).
struct TrialError {
  double translation = 0;  // m, largest over the compared frames
  double rotation = 0;     // rad, largest over the compared frames
  double slip = 0;         // m, largest difference of the end-of-phase displacements
  double vertices = 0;     // m, largest distance of a gripper or object vertex
  bool verdict_agrees = true;
};

// A run's error: the mean of its candidates' errors (NaN ones left out) and how many verdicts
// agree with the reference's.
struct RunError {
  double translation = 0;
  double rotation = 0;
  double slip = 0;
  double vertices = 0;
  int agreeing = 0;
  int candidates = 0;
};

// Whether the protocol holds the grasp, judged by `judge`'s verdict threshold
// (trial::slipped_beyond_threshold) on the recorded displacements and phase times: a run whose
// dt or eps_v moved the protocol's own threshold is judged by the same bar as the reference.
bool held(const io::CandidateRecord& record, const trial::TrialParameters& judge);

// Compares the last `frames` recorded frames of each trajectory (validation_frames + 1: the
// settled grasp, then the validation frames). An unreached phase's displacement (NaN) against
// a reached one counts as the reached one's whole displacement.
TrialError trial_error(const io::CandidateResult& run, const io::CandidateResult& reference,
                       int frames, const trial::TrialParameters& judge);

// Throws std::invalid_argument unless both runs hold the same number of candidates.
RunError run_error(const std::vector<trial::TrialOutcome>& run,
                   const std::vector<trial::TrialOutcome>& reference, int frames,
                   const trial::TrialParameters& judge);

}  // namespace grip::bench
