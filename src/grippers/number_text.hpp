#pragma once
// Shortest text that reads back as exactly the same double, for the asset files grip writes.
#include <charconv>
#include <string>

namespace grip::grippers {

inline std::string number_text(double value) {
  if (value == 0.0) value = 0.0;  // no "-0" in files
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

}  // namespace grip::grippers
