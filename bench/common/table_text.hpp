#pragma once
// Numbers as the benchmarks' Markdown tables write them.
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

namespace grip::bench {

// `value` with `decimals` digits after the point; "-" for NaN (nothing measured).
inline std::string fixed_or_dash(double value, int decimals) {
  if (std::isnan(value)) return "-";
  std::ostringstream text;
  text << std::fixed << std::setprecision(decimals) << value;
  return text.str();
}

}  // namespace grip::bench
