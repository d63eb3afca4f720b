#pragma once
// What is derived from a parameter table (parameter.hpp): reading a file's table of the group
// with every range checked, the range checks of values set in code, each value as text (the
// dataset's provenance), and the docs' Markdown table.
#include <algorithm>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "src/config/config.hpp"
#include "src/config/parameter.hpp"

namespace grip::config {

// What a value must be, after "must " ("be positive (m/s)", "lie strictly between 0 and 1", "be
// a whole number from 1 to 100"); `whole` for a count.
std::string range_words(const Range& range, bool whole, std::string_view unit,
                        std::string_view must = {});
// The range in a table's words: "> 0", "[0, 1)", ">= 1", "1 to 100".
std::string range_text(const Range& range, bool whole);
// The shortest decimal text that reads back as the same double ("0.01", "3e+06").
std::string number_text(double value);
// The command-line option of a key: "--squeeze-speed" for "squeeze_speed".
std::string option_name(std::string_view key);

template <class Group>
bool in_section(const Parameter<Group>& row, std::string_view section) {
  return row.section == section;
}

// The keys of the rows a file's table `section` takes (empty: the group's own table).
template <class Group>
std::vector<std::string_view> parameter_keys(ParameterTable<Group> rows,
                                             std::string_view section = {}) {
  std::vector<std::string_view> keys;
  for (const Parameter<Group>& row : rows) {
    if (in_section(row, section)) keys.push_back(row.key);
  }
  return keys;
}

// Reads the rows of `section` that `table` gives into `values`, each checked against its range
// (ConfigError at the key's line); the others keep their values.
template <class Group>
void read_parameters(const Table& table, ParameterTable<Group> rows, Group& values,
                     std::string_view section = {}) {
  for (const Parameter<Group>& row : rows) {
    if (!in_section(row, section) || !table.has(row.key)) continue;
    if (row.automatic && table.is_string(row.key)) {
      table.choice(row.key, {"auto"});
      values.*row.automatic = true;
      continue;
    }
    if (row.count) {
      // A count is an int: at most 2^31 - 1 where the range sets no bound.
      const double most = std::min<double>(row.range.max, std::numeric_limits<int>::max());
      values.*row.count = table.count_or(row.key, values.*row.count,
                                         static_cast<int>(row.range.min), static_cast<int>(most));
      continue;
    }
    const double value = table.number(row.key);
    if (!row.range.contains(value)) {
      table.fail(row.key, "must " + range_words(row.range, false, row.unit, row.must));
    }
    values.*row.real = value;
  }
}

// Throws std::invalid_argument("<what> <key> must ...") for the first value out of its range.
template <class Group>
void check_parameters(ParameterTable<Group> rows, const Group& values, std::string_view what) {
  for (const Parameter<Group>& row : rows) {
    if (row.automatic && values.*row.automatic) continue;
    const double value = row.real ? values.*row.real : static_cast<double>(values.*row.count);
    if (!row.range.contains(value)) {
      throw std::invalid_argument(std::string(what) + " " + std::string(row.key) + " must " +
                                  range_words(row.range, row.count != nullptr, row.unit, row.must));
    }
  }
}

// The value as the dataset's provenance and the docs write it: a number, or "auto".
template <class Group>
std::string value_text(const Parameter<Group>& row, const Group& values) {
  if (row.automatic && values.*row.automatic) return "auto";
  return row.real ? number_text(values.*row.real) : std::to_string(values.*row.count);
}

// The docs' table of the rows of `section`: key, default, unit, allowed values, meaning.
template <class Group>
std::string markdown_table(ParameterTable<Group> rows, const Group& defaults,
                           std::string_view section = {}) {
  std::string text =
      "| key | default | unit | allowed | meaning |\n| --- | --- | --- | --- | --- |\n";
  for (const Parameter<Group>& row : rows) {
    if (!in_section(row, section)) continue;
    std::string allowed = range_text(row.range, row.count != nullptr);
    if (row.automatic) allowed += ", or `\"auto\"`";
    text += "| `" + std::string(row.key) + "` | " + value_text(row, defaults) + " | " +
            (row.unit.empty() ? "-" : std::string(row.unit)) + " | " + allowed + " | " +
            std::string(row.doc) + " |\n";
  }
  return text;
}

}  // namespace grip::config
