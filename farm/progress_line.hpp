#pragma once
// Rank 0's progress line after each commit: trials done, rate and estimated time left.
#include <cstdint>
#include <string>

namespace grip::farm {

class ProgressLine {
 public:
  explicit ProgressLine(std::uint64_t total) : total_(total) {}
  // "48/120 trials (40.0%), 1.25 trials/s, ETA 58 s"
  std::string text(std::uint64_t done, double seconds) const;
  void log(std::uint64_t done, double seconds) const;  // logs text() (spdlog)

 private:
  std::uint64_t total_;
};

}  // namespace grip::farm
