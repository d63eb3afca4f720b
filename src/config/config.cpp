#include "src/config/config.hpp"

#include <toml++/toml.h>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace grip::config {

struct Source {
  std::filesystem::path file;
  std::string text;
  toml::table root;
};

namespace {

const toml::table& as_table(const void* node) { return *static_cast<const toml::table*>(node); }
const toml::node& as_node(const void* node) { return *static_cast<const toml::node*>(node); }

std::string type_name(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a number";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::date:
      return "a date";
    case toml::node_type::time:
      return "a time";
    case toml::node_type::date_time:
      return "a date-time";
    default:
      return "nothing";
  }
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

[[noreturn]] void raise(const std::filesystem::path& file, std::int64_t line,
                        std::string_view message) {
  std::ostringstream out;
  out << file.string();
  if (line > 0) out << ':' << line;
  out << ": " << message;
  throw ConfigError(out.str());
}

std::int64_t line_of(const toml::node& node) { return node.source().begin.line; }

double finite_number(const toml::node& node, const std::filesystem::path& file,
                     const std::string& key_path) {
  double value = 0;
  if (const auto* i = node.as_integer()) {
    value = static_cast<double>(i->get());
  } else if (const auto* f = node.as_floating_point()) {
    value = f->get();
  } else {
    raise(file, line_of(node), "key '" + key_path + "' must be a number, not " + type_name(node));
  }
  if (!std::isfinite(value)) {
    raise(file, line_of(node),
          "key '" + key_path + "' must be a finite number, not " + std::to_string(value));
  }
  return value;
}

std::shared_ptr<const Source> parse_source(std::string text, const std::filesystem::path& file) {
  auto source = std::make_shared<Source>();
  source->file = file;
  source->text = std::move(text);
  try {
    source->root = toml::parse(source->text, file.string());
  } catch (const toml::parse_error& e) {
    raise(file, e.source().begin.line,
          "TOML syntax error at column " + std::to_string(e.source().begin.column) + ": " +
              std::string(e.description()));
  }
  return source;
}

}  // namespace

Document Document::load(const std::filesystem::path& file) {
  // A folder opens as a stream that reads as empty, which would be parsed as an empty file.
  if (std::filesystem::is_directory(file)) raise(file, 0, "is a directory, not a file");
  std::ifstream in(file, std::ios::binary);
  if (!in) raise(file, 0, "cannot open the file (does it exist and is it readable?)");
  std::ostringstream text;
  text << in.rdbuf();
  return Document(parse_source(text.str(), file));
}

Document Document::parse(std::string text, const std::filesystem::path& name) {
  return Document(parse_source(std::move(text), name));
}

Table Document::root() const { return Table(source_, &source_->root, ""); }
const std::string& Document::text() const { return source_->text; }
const std::filesystem::path& Document::file() const { return source_->file; }

const std::filesystem::path& Table::file() const { return source_->file; }

std::string Table::key_path(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

const void* Table::find(std::string_view key) const { return as_table(node_).get(key); }

const void* Table::require(std::string_view key) const {
  const void* node = find(key);
  if (!node) {
    const std::string where = path_.empty() ? "at the top level" : "in [" + path_ + "]";
    raise(source_->file, line_of(as_table(node_)),
          "missing required key '" + key_path(key) + "' " + where);
  }
  return node;
}

void Table::fail(std::string_view key, std::string_view message) const {
  const void* node = find(key);
  const std::int64_t line = node ? line_of(as_node(node)) : line_of(as_table(node_));
  raise(source_->file, line, "key '" + key_path(key) + "' " + std::string(message));
}

std::string Table::location(std::string_view key) const {
  const void* node = find(key);
  const std::int64_t line = node ? line_of(as_node(node)) : line_of(as_table(node_));
  return source_->file.string() + ":" + std::to_string(line);
}

void Table::allow(std::initializer_list<std::string_view> keys) const {
  allow(std::vector<std::string_view>(keys));
}

void Table::allow(const std::vector<std::string_view>& first,
                  std::initializer_list<std::string_view> more) const {
  std::vector<std::string_view> keys(first);
  keys.insert(keys.end(), more.begin(), more.end());
  for (const auto& [key, value] : as_table(node_)) {
    const std::string_view name = key.str();
    if (std::find(keys.begin(), keys.end(), name) != keys.end()) continue;
    std::string message = "unknown key '" + key_path(name) + "'";
    std::string_view closest;
    std::size_t best = std::max<std::size_t>(2, name.size() / 3) + 1;
    for (const auto& candidate : keys) {
      const std::size_t d = edit_distance(name, candidate);
      if (d < best) best = d, closest = candidate;
    }
    if (!closest.empty()) message += "; did you mean '" + key_path(closest) + "'?";
    message += " Allowed keys " +
               (path_.empty() ? std::string("at the top level") : "in [" + path_ + "]") + ": ";
    bool first = true;
    for (const auto& candidate : keys) {
      message += (first ? "" : ", ") + std::string(candidate);
      first = false;
    }
    raise(source_->file, key.source().begin.line, message);
  }
}

bool Table::has(std::string_view key) const { return find(key) != nullptr; }

bool Table::is_string(std::string_view key) const {
  const void* node = find(key);
  return node && as_node(node).is_string();
}

double Table::number(std::string_view key) const {
  return finite_number(as_node(require(key)), source_->file, key_path(key));
}

double Table::number_or(std::string_view key, double fallback) const {
  return has(key) ? number(key) : fallback;
}

std::int64_t Table::integer(std::string_view key) const {
  const auto& node = as_node(require(key));
  if (const auto* i = node.as_integer()) return i->get();
  raise(source_->file, line_of(node),
        "key '" + key_path(key) + "' must be an integer, not " + type_name(node));
}

std::int64_t Table::integer_or(std::string_view key, std::int64_t fallback) const {
  return has(key) ? integer(key) : fallback;
}

int Table::count_or(std::string_view key, int fallback, int least, int most) const {
  const std::int64_t value = integer_or(key, fallback);
  if (value < least || value > most) {
    fail(key, "must be a whole number from " + std::to_string(least) + " to " +
                  std::to_string(most) + ", not " + std::to_string(value));
  }
  return static_cast<int>(value);
}

bool Table::boolean(std::string_view key) const {
  const auto& node = as_node(require(key));
  if (const auto* b = node.as_boolean()) return b->get();
  raise(source_->file, line_of(node),
        "key '" + key_path(key) + "' must be true or false, not " + type_name(node));
}

bool Table::boolean_or(std::string_view key, bool fallback) const {
  return has(key) ? boolean(key) : fallback;
}

std::string Table::string(std::string_view key) const {
  const auto& node = as_node(require(key));
  if (const auto* s = node.as_string()) return s->get();
  raise(source_->file, line_of(node),
        "key '" + key_path(key) + "' must be a string, not " + type_name(node));
}

std::string Table::string_or(std::string_view key, std::string_view fallback) const {
  return has(key) ? string(key) : std::string(fallback);
}

std::string Table::choice(std::string_view key,
                          std::initializer_list<std::string_view> allowed) const {
  return choice(key, std::span<const std::string_view>(allowed.begin(), allowed.size()));
}

std::string Table::choice(std::string_view key, std::span<const std::string_view> allowed) const {
  std::string value = string(key);
  if (std::find(allowed.begin(), allowed.end(), value) != allowed.end()) return value;
  std::string list;
  for (const auto& a : allowed) list += (list.empty() ? "\"" : ", \"") + std::string(a) + "\"";
  fail(key, "is \"" + value + "\" but must be one of " + list);
}

std::string Table::choice_or(std::string_view key, std::initializer_list<std::string_view> allowed,
                             std::string_view fallback) const {
  return has(key) ? choice(key, allowed) : std::string(fallback);
}

std::vector<double> Table::numbers(std::string_view key) const {
  const auto& node = as_node(require(key));
  const auto* array = node.as_array();
  if (!array) {
    raise(source_->file, line_of(node),
          "key '" + key_path(key) + "' must be an array of numbers, not " + type_name(node));
  }
  std::vector<double> values;
  for (std::size_t i = 0; i < array->size(); ++i) {
    values.push_back(
        finite_number((*array)[i], source_->file, key_path(key) + "[" + std::to_string(i) + "]"));
  }
  return values;
}

std::array<double, 3> Table::vec3(std::string_view key) const {
  const std::vector<double> values = numbers(key);
  if (values.size() != 3) {
    fail(key, "must hold 3 numbers [x, y, z], not " + std::to_string(values.size()));
  }
  return {values[0], values[1], values[2]};
}

std::array<double, 3> Table::vec3_or(std::string_view key, std::array<double, 3> fallback) const {
  return has(key) ? vec3(key) : fallback;
}

std::vector<std::string> Table::strings(std::string_view key) const {
  const auto& node = as_node(require(key));
  const auto* array = node.as_array();
  std::vector<std::string> values;
  if (array) {
    for (const auto& element : *array) {
      const auto* s = element.as_string();
      if (!s) break;
      values.push_back(s->get());
    }
  }
  if (!array || values.size() != array->size()) {
    raise(source_->file, line_of(node), "key '" + key_path(key) + "' must be an array of strings");
  }
  return values;
}

Table Table::table(std::string_view key) const {
  const auto& node = as_node(require(key));
  if (const auto* t = node.as_table()) return Table(source_, t, key_path(key));
  raise(source_->file, line_of(node),
        "key '" + key_path(key) + "' must be a table, not " + type_name(node));
}

std::optional<Table> Table::optional_table(std::string_view key) const {
  if (!has(key)) return std::nullopt;
  return table(key);
}

std::vector<Table> Table::tables(std::string_view key) const {
  const void* found = find(key);
  if (!found) return {};
  const auto& node = as_node(found);
  const auto* array = node.as_array();
  if (!array || !array->is_array_of_tables()) {
    raise(source_->file, line_of(node),
          "key '" + key_path(key) + "' must be an array of tables ([[" + key_path(key) +
              "]]), not " + type_name(node));
  }
  std::vector<Table> result;
  for (std::size_t i = 0; i < array->size(); ++i) {
    result.push_back(
        Table(source_, (*array)[i].as_table(), key_path(key) + "[" + std::to_string(i) + "]"));
  }
  return result;
}

}  // namespace grip::config
