#pragma once
// The candidate file `grip synth` writes and the trial reads: a line-oriented text format
// (docs/synthesis.md) that carries each hand's pose both as the dataset's row-major 3x4
// [R | t] and as position + unit quaternion, with joints, contacts and energy terms.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "src/synth/candidate.hpp"

namespace grip::synth {

// The object the candidates were synthesized on, as `grip synth` was told: its spec (a
// category name or a mesh path), seed and scale, and for a mesh file the hash of its bytes
// (object_file_hash), so that a trial builds the same object or says why it cannot.
struct CandidateObject {
  std::string spec;
  std::uint64_t seed = 0;
  double scale = 1.0;
  std::string content_hash;  // empty for a category
};

struct CandidateFile {
  CandidateObject object;
  std::string gripper;  // its name: a built-in gripper's, or a described gripper's [gripper] name
  std::vector<Candidate> candidates;
};

// Throws std::invalid_argument if a candidate is not of `gripper`'s kind or the candidates mix
// hand counts or energy names, std::runtime_error naming the file if it cannot be written.
// Numbers are written with 17 significant digits, so reading gives back the same doubles.
void write_candidates(const std::filesystem::path& file, const CandidateObject& object,
                      const grippers::GripperType& gripper,
                      const std::vector<Candidate>& candidates);

// The most candidates a candidate file holds and `grip synth --count` makes.
inline constexpr int kMaxCandidates = 1'000'000;

// How far from the object's origin a hand position or a contact point may lie (m): farther, a
// candidate grasps nothing and its trial would waste the solver's time.
inline constexpr double kMaxCandidateDistance = 10.0;

// Throws std::runtime_error naming the file, the line and the field for anything but what
// write_candidates writes: a number that is not finite, a quaternion that is not of unit norm,
// a hand position or contact point farther than kMaxCandidateDistance from the object's origin,
// more than kMaxCandidates candidates, more energies or contacts than their line holds.
CandidateFile read_candidates(const std::filesystem::path& file);

}  // namespace grip::synth
