#include "src/json/json_text.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

namespace grip::json {
namespace {

using Json = nlohmann::ordered_json;

std::vector<std::string> split_path(const std::string& path) {
  std::vector<std::string> keys;
  for (std::size_t start = 0; start < path.size();) {
    const std::size_t end = std::min(path.find('/', start + 1), path.size());
    keys.push_back(path.substr(start + 1, end - start - 1));
    start = end;
  }
  return keys;
}

class Writer {
 public:
  Writer(const char* number_format, const std::vector<Block>& blocks, bool spaced)
      : number_format_(number_format),
        item_separator_(spaced ? ", " : ","),
        key_separator_(spaced ? ": " : ":") {
    for (const Block& block : blocks) blocks_.push_back({split_path(block.path), block.indent});
  }

  void write(const Json& value, int line_indent) {
    if (value.is_object() || value.is_array()) {
      write_container(value, line_indent);
    } else if (value.is_number_float()) {
      write_number(value.get<double>());
    } else {
      write_scalar(value);
    }
  }

  std::string text;

 private:
  struct PathBlock {
    std::vector<std::string> keys;
    int indent = 0;
  };

  // The indent of the block at the current path; -1 when it stays on one line.
  int block_indent() const {
    for (const PathBlock& block : blocks_) {
      if (block.keys.size() != path_.size()) continue;
      bool match = true;
      for (std::size_t i = 0; i < path_.size() && match; ++i) {
        match = block.keys[i] == "*" || block.keys[i] == path_[i];
      }
      if (match) return block.indent;
    }
    return -1;
  }

  void write_container(const Json& value, int line_indent) {
    const bool object = value.is_object();
    const int indent = block_indent();
    text += object ? '{' : '[';
    std::size_t index = 0;
    for (auto item = value.begin(); item != value.end(); ++item, ++index) {
      if (index) text += indent < 0 ? item_separator_ : ",";
      if (indent >= 0) text += '\n' + std::string(indent, ' ');
      if (object) {
        write_scalar(Json(item.key()));
        text += key_separator_;
      }
      path_.push_back(object ? item.key() : std::to_string(index));
      write(item.value(), indent < 0 ? line_indent : indent);
      path_.pop_back();
    }
    if (indent >= 0) text += '\n' + std::string(line_indent, ' ');
    text += object ? '}' : ']';
  }

  void write_number(double value) {
    if (!std::isfinite(value)) {
      text += "null";  // JSON has no infinity or NaN
      return;
    }
    char buffer[32];
    const int size = std::snprintf(buffer, sizeof buffer, number_format_, value);
    if (size < static_cast<int>(sizeof buffer)) {
      text.append(buffer, size);
    } else {
      std::string wide(size, '\0');
      std::snprintf(wide.data(), wide.size() + 1, number_format_, value);
      text += wide;
    }
  }

  void write_scalar(const Json& value) {
    text += value.dump(-1, ' ', false, Json::error_handler_t::replace);
  }

  const char* number_format_;
  const char* item_separator_;
  const char* key_separator_;
  std::vector<PathBlock> blocks_;
  std::vector<std::string> path_;
};

}  // namespace

std::string text(const nlohmann::ordered_json& value, const char* number_format,
                 const std::vector<Block>& blocks) {
  Writer writer(number_format, blocks, true);
  writer.write(value, 0);
  return std::move(writer.text);
}

std::string compact_text(const nlohmann::ordered_json& value, const char* number_format) {
  Writer writer(number_format, {}, false);
  writer.write(value, 0);
  return std::move(writer.text);
}

}  // namespace grip::json
