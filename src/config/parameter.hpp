#pragma once
// A group of settings said once (MuJoCo's mjxmacro.h, Drake's Serialize): one table per group,
// each row a parameter's key, its field in the group's struct, its range, unit and one line of
// doc. The job and scene readers, the command-line options, the range checks, the dataset's
// provenance and the docs' tables are derived from the rows (parameter_table.hpp), so adding a
// parameter is adding a row.
#include <cmath>
#include <limits>
#include <span>
#include <string>
#include <string_view>

namespace grip::config {

// The values a parameter allows: an interval, each end open or closed; an infinite end is no
// bound. Values must be finite.
struct Range {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_open = false;
  bool max_open = false;

  static constexpr Range positive() {
    return {0.0, std::numeric_limits<double>::infinity(), true, false};
  }
  static constexpr Range at_least(double least) {
    return {least, std::numeric_limits<double>::infinity(), false, false};
  }
  static constexpr Range from_to(double least, double most) { return {least, most, false, false}; }
  static constexpr Range strictly_between(double low, double high) {
    return {low, high, true, true};
  }

  bool contains(double value) const {
    return std::isfinite(value) && (min_open ? value > min : value >= min) &&
           (max_open ? value < max : value <= max);
  }
};

// One row. Exactly one of `real` and `count` is set.
template <class Group>
struct Parameter {
  std::string_view key = {};  // as a file writes it; the option is --key with '_' as '-'
  double Group::*real = nullptr;
  int Group::*count = nullptr;
  Range range;
  std::string_view unit = {};  // SI ("m/s", "N"); "" for a pure number
  std::string_view doc = {};   // one line: what the value does
  // A real that may be "auto" instead of a number (kappa): the flag that word sets.
  bool Group::*automatic = nullptr;
  // Where a job file sets it when not in the group's own table ("outputs": the frame counts).
  std::string_view section = {};
  // The range in words where the generic ones say too little ("a non-negative time (s, ...)").
  std::string_view must = {};
};

template <class Group>
using ParameterTable = std::span<const Parameter<Group>>;

}  // namespace grip::config
