#pragma once
// Portable random numbers for one synthesis attempt: the generator is seeded from (seed,
// stream, attempt index), so an attempt draws the same numbers whatever thread runs it.
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>

namespace grip::synth {

class CandidateRandom {
 public:
  CandidateRandom(std::uint64_t seed, std::uint32_t stream, std::uint64_t index)
      : generator_(engine(seed, stream, index)) {}

  // Uniform in [0, 1) with 53 random bits (std distributions differ between libraries).
  double uniform() { return static_cast<double>(generator_() >> 11) * 0x1.0p-53; }
  double uniform(double min, double max) { return min + (max - min) * uniform(); }
  // Uniform integer in [0, n) for n > 0.
  int below(int n) { return static_cast<int>(uniform() * n); }
  // Standard normal (Box-Muller).
  double normal() {
    const double u = 1.0 - uniform();
    return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * std::numbers::pi * uniform());
  }

 private:
  static std::mt19937_64 engine(std::uint64_t seed, std::uint32_t stream, std::uint64_t index) {
    std::seed_seq sequence{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32),
                           stream, static_cast<std::uint32_t>(index),
                           static_cast<std::uint32_t>(index >> 32)};
    return std::mt19937_64(sequence);
  }

  std::mt19937_64 generator_;
};

}  // namespace grip::synth
