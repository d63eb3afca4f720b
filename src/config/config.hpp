#pragma once
// The strict TOML reader under every grip file format (scenes, jobs): a misspelt key, a wrong
// type, a missing required key or a non-finite number is a one-line error naming the file,
// the line, the key and, for unknown keys, the keys that are allowed.
#include <array>
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace grip::config {

// Formatted "FILE:LINE: message" (one line), ready to show a user as is.
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Source;  // the parsed file; defined in config.cpp so toml++ stays in one translation unit

// A view of one table of a parsed file. Getters take keys relative to this table.
class Table {
 public:
  // Declares every key this table may hold. Any other key is an error that suggests the
  // closest allowed key and lists them all. Call it before reading values.
  void allow(std::initializer_list<std::string_view> keys) const;
  // The same for keys of two lists: a shared list (a parameter table's) and a table's own.
  void allow(const std::vector<std::string_view>& keys,
             std::initializer_list<std::string_view> more = {}) const;

  bool has(std::string_view key) const;
  bool is_string(std::string_view key) const;  // for values that are "a number or a word"

  double number(std::string_view key) const;  // integer or float, finite
  double number_or(std::string_view key, double fallback) const;
  std::int64_t integer(std::string_view key) const;
  std::int64_t integer_or(std::string_view key, std::int64_t fallback) const;
  // A count that must lie in [least, most], checked as the 64-bit integer the file holds (not
  // after a cast that wraps): "key 'sim.max_newton_iters' must be a whole number from 1 to ...".
  int count_or(std::string_view key, int fallback, int least, int most) const;
  bool boolean(std::string_view key) const;
  bool boolean_or(std::string_view key, bool fallback) const;
  std::string string(std::string_view key) const;
  std::string string_or(std::string_view key, std::string_view fallback) const;
  // A string that must be one of `allowed`; the error lists them.
  std::string choice(std::string_view key, std::initializer_list<std::string_view> allowed) const;
  std::string choice(std::string_view key, std::span<const std::string_view> allowed) const;
  std::string choice_or(std::string_view key, std::initializer_list<std::string_view> allowed,
                        std::string_view fallback) const;
  std::array<double, 3> vec3(std::string_view key) const;
  std::array<double, 3> vec3_or(std::string_view key, std::array<double, 3> fallback) const;
  std::vector<double> numbers(std::string_view key) const;
  std::vector<std::string> strings(std::string_view key) const;

  Table table(std::string_view key) const;
  std::optional<Table> optional_table(std::string_view key) const;
  std::vector<Table> tables(std::string_view key) const;  // an array of tables; empty if absent

  // Reports a value that parsed but breaks a rule only the caller knows (e.g. dt <= 0), in the
  // same one-line format, at the key's line.
  [[noreturn]] void fail(std::string_view key, std::string_view message) const;
  // "FILE:LINE" of the key (of this table when the key is absent), for a check made later.
  std::string location(std::string_view key) const;

  const std::filesystem::path& file() const;
  const std::string& path() const { return path_; }  // dotted key path, "" for the root

 private:
  friend class Document;
  Table(std::shared_ptr<const Source> source, const void* node, std::string path)
      : source_(std::move(source)), node_(node), path_(std::move(path)) {}

  std::string key_path(std::string_view key) const;
  const void* find(std::string_view key) const;     // the toml::node, or nullptr
  const void* require(std::string_view key) const;  // the toml::node, or a missing-key error

  std::shared_ptr<const Source> source_;
  const void* node_;  // a toml::table owned by source_
  std::string path_;
};

// A parsed configuration file. Keeps its text (a dataset records the job file verbatim).
class Document {
 public:
  static Document load(const std::filesystem::path& file);
  static Document parse(std::string text, const std::filesystem::path& name);

  Table root() const;
  const std::string& text() const;
  const std::filesystem::path& file() const;

 private:
  explicit Document(std::shared_ptr<const Source> source) : source_(std::move(source)) {}
  std::shared_ptr<const Source> source_;
};

}  // namespace grip::config
