#pragma once
// Uniform random numbers that are identical on every platform for a given seed and stream:
// std::mt19937_64's output is fixed by the standard, std::uniform_real_distribution's is not.
#include <cstdint>
#include <random>

namespace grip::objects {

class SeededUniform {
 public:
  // `stream` separates independent sequences drawn from one seed (e.g. one per category).
  SeededUniform(std::uint64_t seed, std::uint32_t stream) : generator_(engine(seed, stream)) {}

  // Uniform in [0, 1) with 53 random bits.
  double operator()() { return static_cast<double>(generator_() >> 11) * 0x1.0p-53; }

  double operator()(double min, double max) { return min + (max - min) * (*this)(); }

 private:
  static std::mt19937_64 engine(std::uint64_t seed, std::uint32_t stream) {
    std::seed_seq sequence{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32),
                           stream};
    return std::mt19937_64(sequence);
  }

  std::mt19937_64 generator_;
};

}  // namespace grip::objects
