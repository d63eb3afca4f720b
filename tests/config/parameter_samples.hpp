// Values of a parameter table's rows for the tests that check each row reaches every place
// derived from the table: one the row allows other than its default, and one it refuses.
#pragma once

#include <cmath>
#include <string>

#include "src/config/parameter_table.hpp"

namespace grip::config::testing {

// A value inside the row's range other than `defaults`' (twice it, or one more), as text.
template <class Group>
std::string inside_value(const Parameter<Group>& row, const Group& defaults) {
  if (row.count) {
    const int value = defaults.*row.count;
    const int doubled = value > 0 ? 2 * value : value + 1;
    return std::to_string(row.range.contains(doubled) ? doubled : value + 1);
  }
  const double value = defaults.*row.real;
  for (const double candidate : {1.5 * value, 0.75 * value, value + 1.0}) {
    if (candidate != value && row.range.contains(candidate)) return number_text(candidate);
  }
  return number_text(0.5 * (row.range.min + row.range.max));
}

// A value outside the row's range, as text.
template <class Group>
std::string outside_value(const Parameter<Group>& row) {
  const double below = row.range.min_open ? row.range.min : row.range.min - 1.0;
  return row.count ? std::to_string(static_cast<long long>(below)) : number_text(below);
}

// The value the text reads as, in the row's field of `values`.
template <class Group>
double field_value(const Parameter<Group>& row, const Group& values) {
  return row.real ? values.*row.real : static_cast<double>(values.*row.count);
}

}  // namespace grip::config::testing
