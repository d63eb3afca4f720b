#pragma once
// The device check's measure of agreement between the device's values and the host
// launcher's.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace grip::solver::parallel {

// The largest |a - b| over blocks of `block` values, each relative to its block's largest |b|;
// infinite where a value is not a number or the two differ in length, so that neither passes.
inline double relative_difference(const std::vector<double>& a, const std::vector<double>& b,
                                  std::size_t block) {
  if (a.size() != b.size()) return std::numeric_limits<double>::infinity();
  double worst = 0.0;
  for (std::size_t first = 0; first < b.size(); first += block) {
    double scale = 0.0, difference = 0.0;
    for (std::size_t i = first; i < std::min(first + block, b.size()); ++i) {
      scale = std::max(scale, std::abs(b[i]));
      const double d = std::abs(a[i] - b[i]);
      if (std::isnan(d)) return std::numeric_limits<double>::infinity();
      difference = std::max(difference, d);
    }
    if (difference > 0.0) worst = std::max(worst, difference / std::max(scale, 1e-300));
  }
  return worst;
}

}  // namespace grip::solver::parallel
