// The strict TOML reader: every kind of bad input is one line naming file, line and key.
#include <gtest/gtest.h>

#include <unistd.h>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "src/config/config.hpp"

namespace grip::config {
namespace {

// The ConfigError message raised by `read` on a document parsed from `text` as `scene.toml`.
template <typename Read>
std::string error_of(const std::string& text, Read read) {
  try {
    read(Document::parse(text, "scene.toml").root());
  } catch (const ConfigError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
    return message;
  }
  ADD_FAILURE() << "no ConfigError for:\n" << text;
  return {};
}

TEST(ConfigReader, MisspeltKeyNamesFileLineKeyAndSuggestion) {
  const std::string text = "[sim]\ndt = 0.01\ndurration = 2.0\n";
  const auto message = error_of(text, [](const Table& root) {
    root.allow({"sim"});
    root.table("sim").allow({"dt", "duration", "gravity"});
  });
  EXPECT_EQ(message,
            "scene.toml:3: unknown key 'sim.durration'; did you mean 'sim.duration'? "
            "Allowed keys in [sim]: dt, duration, gravity");
}

TEST(ConfigReader, UnknownTopLevelTableIsAnError) {
  const auto message = error_of("[simulation]\ndt = 1\n", [](const Table& root) {
    root.allow({"sim", "body"});
  });
  EXPECT_NE(message.find("scene.toml:1: unknown key 'simulation'"), std::string::npos) << message;
  EXPECT_NE(message.find("Allowed keys at the top level: sim, body"), std::string::npos);
}

TEST(ConfigReader, FarFromEveryAllowedKeyGetsNoSuggestion) {
  const auto message = error_of("zzzzzz = 1\n", [](const Table& root) { root.allow({"dt"}); });
  EXPECT_EQ(message.find("did you mean"), std::string::npos) << message;
}

TEST(ConfigReader, WrongTypeNamesKeyAndBothTypes) {
  const auto message = error_of("[sim]\n\ndt = \"fast\"\n",
                                [](const Table& root) { root.table("sim").number("dt"); });
  EXPECT_EQ(message, "scene.toml:3: key 'sim.dt' must be a number, not a string");
}

TEST(ConfigReader, MissingRequiredKeyPointsAtItsTable) {
  const auto message = error_of("title = \"x\"\n[sim]\nduration = 1\n",
                                [](const Table& root) { root.table("sim").number("dt"); });
  EXPECT_EQ(message, "scene.toml:2: missing required key 'sim.dt' in [sim]");
}

TEST(ConfigReader, NonFiniteNumbersAreRejected) {
  for (const std::string value : {"nan", "inf", "-inf", "+nan"}) {
    const auto message =
        error_of("dt = " + value + "\n", [](const Table& root) { root.number("dt"); });
    EXPECT_NE(message.find("scene.toml:1: key 'dt' must be a finite number"), std::string::npos)
        << message;
  }
  const auto in_array = error_of("g = [0, nan, 1]\n", [](const Table& root) { root.vec3("g"); });
  EXPECT_NE(in_array.find("key 'g[1]' must be a finite number"), std::string::npos) << in_array;
}

TEST(ConfigReader, IntegersAreNumbersButFloatsAreNotIntegers) {
  const auto doc = Document::parse("a = 3\nb = 2.5\n", "scene.toml");
  EXPECT_EQ(doc.root().number("a"), 3.0);
  EXPECT_EQ(doc.root().integer("a"), 3);
  const auto message = error_of("b = 2.5\n", [](const Table& root) { root.integer("b"); });
  EXPECT_EQ(message, "scene.toml:1: key 'b' must be an integer, not a number");
}

TEST(ConfigReader, FallbacksApplyOnlyWhenKeyIsAbsent) {
  const auto root = Document::parse("a = 1.5\n", "scene.toml").root();
  EXPECT_EQ(root.number_or("a", 7.0), 1.5);
  EXPECT_EQ(root.number_or("b", 7.0), 7.0);
  EXPECT_EQ(root.string_or("c", "auto"), "auto");
  EXPECT_EQ(root.boolean_or("d", true), true);
  const std::array<double, 3> down{0, 0, -9.8};
  EXPECT_EQ(root.vec3_or("g", down), down);
}

TEST(ConfigReader, Vec3NeedsThreeNumbers) {
  const auto message = error_of("g = [0, -9.8]\n", [](const Table& root) { root.vec3("g"); });
  EXPECT_EQ(message, "scene.toml:1: key 'g' must hold 3 numbers [x, y, z], not 2");
  const auto root = Document::parse("g = [0, 0, -9.8]\n", "scene.toml").root();
  EXPECT_EQ(root.vec3("g")[2], -9.8);
}

TEST(ConfigReader, ChoiceListsAllowedWords) {
  const auto message = error_of("type = \"soft\"\n", [](const Table& root) {
    root.choice("type", {"kinematic", "affine", "fem"});
  });
  EXPECT_EQ(message,
            "scene.toml:1: key 'type' is \"soft\" but must be one of \"kinematic\", \"affine\", "
            "\"fem\"");
}

TEST(ConfigReader, ArraysOfTablesCarryTheirIndexInKeyPaths) {
  const std::string text =
      "[[body]]\nname = \"a\"\nyoungs = 1e6\n\n[[body]]\nname = \"b\"\nyoungs = \"stiff\"\n";
  const auto message = error_of(text, [](const Table& root) {
    for (const auto& body : root.tables("body")) body.number("youngs");
  });
  EXPECT_EQ(message, "scene.toml:7: key 'body[1].youngs' must be a number, not a string");
  EXPECT_TRUE(Document::parse("x = 1\n", "scene.toml").root().tables("body").empty());
}

TEST(ConfigReader, CallerRulesUseTheSameFormat) {
  const auto message = error_of("[sim]\ndt = -0.01\n", [](const Table& root) {
    const auto sim = root.table("sim");
    if (sim.number("dt") <= 0) sim.fail("dt", "must be positive (seconds)");
  });
  EXPECT_EQ(message, "scene.toml:2: key 'sim.dt' must be positive (seconds)");
}

TEST(ConfigReader, SyntaxErrorNamesLine) {
  const auto message = error_of("[sim]\ndt = = 1\n", [](const Table&) {});
  EXPECT_NE(message.find("scene.toml:2: TOML syntax error"), std::string::npos) << message;
}

TEST(ConfigReader, LoadsFilesAndKeepsTheirText) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("grip_config_test_job_" + std::to_string(::getpid()) + ".toml");
  const std::string text = "seed = 7\n# a comment\n";
  std::ofstream(path) << text;
  const auto doc = Document::load(path);
  EXPECT_EQ(doc.text(), text);
  EXPECT_EQ(doc.root().integer("seed"), 7);
  std::filesystem::remove(path);

  try {
    Document::load("/nonexistent/dir/job.toml");
    FAIL() << "no error for a missing file";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()),
              "/nonexistent/dir/job.toml: cannot open the file (does it exist and is it "
              "readable?)");
  }
}

}  // namespace
}  // namespace grip::config
