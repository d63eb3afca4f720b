#pragma once
// JSON text of grip's reports in their established layouts: a document built as an
// nlohmann::ordered_json, written with nlohmann's string escaping, the report's own number format
// and one line per item only in the objects and arrays the report lays out so.
#include <nlohmann/json_fwd.hpp>

#include <string>
#include <vector>

namespace grip::json {

// An object or array written one item per line, its items indented by `indent` spaces and its
// closing bracket on a line of its own, indented like the line the block opened on. `path`
// names it from the root by keys and array indices, "*" matching any: "" is the root,
// "/scenes/*" every item of the root's "scenes".
struct Block {
  std::string path;
  int indent = 0;
};

// `value` with ", " and ": " between items, floating-point numbers in printf's `number_format`,
// the objects and arrays `blocks` names one item per line and all else on one line; without a
// final newline. Numbers that are not finite are null and bytes of a string that are not UTF-8
// become U+FFFD, so the text is always valid JSON.
std::string text(const nlohmann::ordered_json& value, const char* number_format,
                 const std::vector<Block>& blocks = {});

// The same on one line with "," and ":" between items.
std::string compact_text(const nlohmann::ordered_json& value, const char* number_format);

}  // namespace grip::json
