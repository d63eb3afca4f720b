// Fuzz target: candidate files (grip synth's output, the trial's input). Anything but the
// std::runtime_error read_candidates documents is a finding.
#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "fuzz/fuzz_input.hpp"
#include "src/synth/candidate_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    grip::synth::read_candidates(grip::fuzz::write_input(data, size, "candidates.txt"));
  } catch (const std::runtime_error&) {
  }
  return 0;
}
