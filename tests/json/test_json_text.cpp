// JSON text in the reports' layouts: separators, blocks one item per line, the report's number
// format, and strings that stay valid JSON whatever bytes they hold.
#include <gtest/gtest.h>

#include <limits>
#include <nlohmann/json.hpp>

#include "src/json/json_text.hpp"

namespace grip::json {
namespace {

using Json = nlohmann::ordered_json;

TEST(JsonText, KeepsKeyOrderAndPutsOnlyTheNamedBlocksOnLines) {
  const Json value = {{"z", 1},
                      {"rows", Json::array({Json{{"b", true}, {"a", nullptr}}, Json::array()})},
                      {"inline", {{"x", Json::array({1, 2})}, {"empty", Json::object()}}},
                      {"empty", Json::array()}};
  EXPECT_EQ(text(value, "%g"), R"({"z": 1, "rows": [{"b": true, "a": null}, []], )"
                               R"("inline": {"x": [1, 2], "empty": {}}, "empty": []})");
  EXPECT_EQ(text(value, "%g", {{"", 0}, {"/rows", 2}, {"/rows/*", 4}, {"/empty", 2}}),
            "{\n"
            "\"z\": 1,\n"
            "\"rows\": [\n"
            "  {\n"
            "    \"b\": true,\n"
            "    \"a\": null\n"
            "  },\n"
            "  [\n"
            "  ]\n"
            "],\n"
            "\"inline\": {\"x\": [1, 2], \"empty\": {}},\n"
            "\"empty\": [\n"
            "]\n"
            "}");
  EXPECT_EQ(compact_text(value, "%g"), R"({"z":1,"rows":[{"b":true,"a":null},[]],)"
                                       R"("inline":{"x":[1,2],"empty":{}},"empty":[]})");
}

TEST(JsonText, WritesFloatsInTheGivenFormatIntegersExactlyAndNonFiniteAsNull) {
  const double inf = std::numeric_limits<double>::infinity();
  const Json value =
      Json::array({0.1, 2.0, -0.0, 1e300, inf, -inf, std::numeric_limits<double>::quiet_NaN(),
                   18446744073709551615u, -9223372036854775807 - 1});
  EXPECT_EQ(text(value, "%.17g"),
            "[0.10000000000000001, 2, -0, 1.0000000000000001e+300, null, null, null, "
            "18446744073709551615, -9223372036854775808]");
  EXPECT_EQ(compact_text(Json::array({0.25, 1.0, 12.345}), "%.1f"), "[0.2,1.0,12.3]");
  // Wider than any fixed buffer: still the whole number.
  EXPECT_EQ(text(Json::array({1e40}), "%.0f").size(), 43u);
}

TEST(JsonText, StringsAndKeysWithQuotesBackslashesAndNewlinesSurviveARoundTrip) {
  const std::string odd = "dir \"quoted\"\\sub\\\nline\ttab\x01 \xc3\xa9";
  const Json value = {{odd, Json::array({odd})}, {"k", odd}};
  for (const std::string& written :
       {text(value, "%g"), text(value, "%g", {{"", 2}, {"/*", 4}}), compact_text(value, "%g")}) {
    const Json read = Json::parse(written);
    EXPECT_EQ(read, value) << written;
  }
}

TEST(JsonText, BytesThatAreNotUtf8BecomeReplacementCharacters) {
  const std::string written = text(Json{{"path", "caf\xe9.toml"}}, "%g");
  Json read;
  ASSERT_NO_THROW(read = Json::parse(written)) << written;
  EXPECT_EQ(read["path"], "caf\xef\xbf\xbd.toml");
}

}  // namespace
}  // namespace grip::json
