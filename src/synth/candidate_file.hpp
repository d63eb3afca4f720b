#pragma once
// The candidate file `grip synth` writes and the trial reads: a line-oriented text format
// (docs/synthesis.md) that carries each hand's pose both as the dataset's row-major 3x4
// [R | t] and as position + unit quaternion, with joints, contacts and energy terms.
#include <filesystem>
#include <vector>

#include "src/synth/candidate.hpp"

namespace grip::synth {

// Throws std::invalid_argument if the candidates mix grippers, hand counts or energy names,
// std::runtime_error naming the file if it cannot be written. Numbers are written with 17
// significant digits, so reading gives back the same doubles.
void write_candidates(const std::filesystem::path& file, const std::vector<Candidate>& candidates);

// Throws std::runtime_error naming the file, the line and what was expected.
std::vector<Candidate> read_candidates(const std::filesystem::path& file);

}  // namespace grip::synth
