#include "farm/progress_line.hpp"

#include <spdlog/spdlog.h>

#include <cmath>

namespace grip::farm {
namespace {

std::string duration(double seconds) {
  const auto s = static_cast<long long>(std::llround(seconds));
  if (s < 120) return fmt::format("{} s", s);
  if (s < 7200) return fmt::format("{} min {} s", s / 60, s % 60);
  return fmt::format("{} h {} min", s / 3600, (s % 3600) / 60);
}

}  // namespace

std::string ProgressLine::text(std::uint64_t done, double seconds) const {
  const double fraction = total_ ? static_cast<double>(done) / static_cast<double>(total_) : 1.0;
  const double rate = seconds > 0 ? static_cast<double>(done) / seconds : 0.0;
  std::string line =
      fmt::format("{}/{} trials ({:.1f}%), {:.2f} trials/s", done, total_, 100.0 * fraction, rate);
  if (done < total_ && rate > 0) {
    line += ", ETA " + duration(static_cast<double>(total_ - done) / rate);
  }
  return line;
}

void ProgressLine::log(std::uint64_t done, double seconds) const {
  spdlog::info("{}", text(done, seconds));
}

}  // namespace grip::farm
