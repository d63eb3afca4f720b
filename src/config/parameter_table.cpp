#include "src/config/parameter_table.hpp"

#include <charconv>
#include <limits>

namespace grip::config {
namespace {

// Built by appending: a chain of + draws a false -Wrestrict warning from GCC 12.
std::string with_unit(std::string words, std::string_view unit) {
  if (unit.empty()) return words;
  words += " (";
  words += unit;
  words += ')';
  return words;
}

std::string count_text(double value) { return std::to_string(static_cast<long long>(value)); }

std::string interval(const Range& range) {
  std::string text = range.min_open ? "(" : "[";
  text += number_text(range.min);
  text += ", ";
  text += number_text(range.max);
  text += range.max_open ? ')' : ']';
  return text;
}

}  // namespace

std::string number_text(double value) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, value).ptr;
  return std::string(text, end);
}

std::string option_name(std::string_view key) {
  std::string name = "--" + std::string(key);
  for (char& c : name) c = c == '_' ? '-' : c;
  return name;
}

std::string range_words(const Range& range, bool whole, std::string_view unit,
                        std::string_view must) {
  if (!must.empty()) return "be " + std::string(must);
  const bool bounded = std::isfinite(range.max);
  if (whole) {
    // A count is an int: at most 2^31 - 1 where the range sets no bound.
    const double most = bounded ? range.max : std::numeric_limits<int>::max();
    return "be a whole number from " + count_text(range.min) + " to " + count_text(most);
  }
  if (bounded && range.min_open && range.max_open) {
    return "lie strictly between " + number_text(range.min) + " and " + number_text(range.max);
  }
  if (bounded) return "lie in " + interval(range);
  if (range.min == 0 && range.min_open) return with_unit("be positive", unit);
  if (range.min == 0 && unit == "s") return "be a non-negative time (s)";
  if (range.min == 0) return with_unit("be non-negative", unit);
  return with_unit(
      std::string(range.min_open ? "be more than " : "be at least ") + number_text(range.min),
      unit);
}

std::string range_text(const Range& range, bool whole) {
  if (whole) {
    return std::isfinite(range.max) ? count_text(range.min) + " to " + count_text(range.max)
                                    : ">= " + count_text(range.min);
  }
  if (std::isfinite(range.max)) return interval(range);
  return (range.min_open ? "> " : ">= ") + number_text(range.min);
}

}  // namespace grip::config
