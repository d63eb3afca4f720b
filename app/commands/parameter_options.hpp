#pragma once
// A parameter table's rows as a command's options (src/config/parameter.hpp): --key with '_' as
// '-', its doc and unit as the help, its range checked before any work, as the job reader
// checks it.
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "app/cli/command_line.hpp"
#include "src/config/parameter_table.hpp"

namespace grip::commands {

// "must be a finite number > 0, not 'x'", or "" for a text the row takes.
template <class Group>
std::string parameter_problem(const config::Parameter<Group>& row, const std::string& text) {
  if (row.automatic && text == "auto") return "";
  const std::string rule = config::range_text(row.range, row.count != nullptr);
  const bool bounded = std::isfinite(row.range.max);
  double value = std::nan("");
  if (row.count) {
    std::int64_t whole = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), whole);
    if (error == std::errc() && end == text.data() + text.size()) {
      value = static_cast<double>(whole);
    }
  } else {
    char* end = nullptr;
    const double parsed = std::strtod(text.c_str(), &end);
    if (!text.empty() && *end == '\0') value = parsed;
  }
  if (row.range.contains(value) && (!row.count || value <= 2147483647.0)) return "";
  const std::string what = row.count ? "a whole number " + (bounded ? "from " + rule : rule)
                                     : "a finite number " + (bounded ? "in " + rule : rule);
  return "must be " + what + (row.automatic ? " or \"auto\"" : "") + ", not '" + text + "'";
}

// Declares every row of `rows` as an option of `command` that sets its field of `values`.
template <class Group>
void declare_parameters(cli::Command& command, config::ParameterTable<Group> rows, Group& values) {
  for (const config::Parameter<Group>& row : rows) {
    const std::string help =
        std::string(row.doc) + (row.unit.empty() ? "" : " (" + std::string(row.unit) + ")");
    const cli::Check check =
        cli::Check::custom([row](const std::string& text) { return parameter_problem(row, text); },
                           config::range_text(row.range, row.count != nullptr));
    if (row.automatic) {
      command
          .option_text(
              config::option_name(row.key),
              [&values, row](const std::string& text) {
                values.*row.automatic = text == "auto";
                if (text != "auto") values.*row.real = std::strtod(text.c_str(), nullptr);
              },
              help + "; default " + config::value_text(row, values))
          .check(check);
    } else if (row.real) {
      command.option(config::option_name(row.key), values.*row.real, help)
          .show_default()
          .check(check);
    } else {
      command.option(config::option_name(row.key), values.*row.count, help)
          .show_default()
          .check(check);
    }
  }
}

}  // namespace grip::commands
