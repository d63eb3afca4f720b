// The JSON report of `grip simulate`: its layout, byte for byte, and scene files, body names and
// failures with quotes, backslashes, newlines or bytes that are not UTF-8 kept as valid JSON.
#include <gtest/gtest.h>

#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "src/scene/scene_run.hpp"

namespace grip::scene {
namespace {

// A scene that ran and one that failed before its first step (no contact: min_distance null).
BatchReport two_scenes() {
  BatchReport batch;
  batch.threads = 2;
  batch.wall_seconds = 0.5;
  SceneReport held;
  held.scene = "a.toml";
  held.steps = 2;
  held.bodies = {{"ground", {0, 0, -0.01}, {0, 0, 0}, Eigen::Matrix3d::Identity()},
                 {"box", {0.1, 0, 0.05}, {0, 0, -0.1}, Eigen::Matrix3d::Identity()}};
  held.min_distance = 0.00093;
  held.newton_total = 7;
  held.newton_max_per_step = 4;
  held.trace = {{0.01, {{0, 0, -0.01}, {0.1, 0, 0.0625}}}, {0.02, {{0, 0, -0.01}, {0.1, 0, 0.05}}}};
  SceneReport failed;
  failed.scene = "b.toml";
  failed.ok = false;
  failed.failure = "t = 0.01 s: Newton did not converge in 100 iterations";
  failed.bodies = {{"ball", {0, 0, 1}, {0, 0, 0}, Eigen::Matrix3d::Identity()}};
  failed.min_volume_ratio = 0.5;
  batch.scenes = {held, failed};
  return batch;
}

std::string report_text(const BatchReport& batch, bool trace) {
  std::ostringstream out;
  write_json(out, batch, trace);
  return out.str();
}

TEST(SceneReport, KeepsItsLayout) {
  const std::string expected = R"({
"threads": 2,
"wall_seconds": 0.5,
"scenes": [
{
  "scene": "a.toml",
  "status": "ok",
  "failure": null,
  "steps": 2,
  "bodies": {
    "ground": {"com": [0, 0, -0.01], "velocity": [0, 0, 0], "rotation": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]},
    "box": {"com": [0.10000000000000001, 0, 0.050000000000000003], "velocity": [0, 0, -0.10000000000000001], "rotation": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}
  },
  "min_distance": 0.00093000000000000005,
  "min_volume_ratio": 1,
  "intersection_free": true,
  "newton_iterations": {"total": 7, "max_per_step": 4},
  "trace": [
    {"t": 0.01, "com": {"ground": [0, 0, -0.01], "box": [0.10000000000000001, 0, 0.0625]}},
    {"t": 0.02, "com": {"ground": [0, 0, -0.01], "box": [0.10000000000000001, 0, 0.050000000000000003]}}
  ]
},
{
  "scene": "b.toml",
  "status": "failed",
  "failure": "t = 0.01 s: Newton did not converge in 100 iterations",
  "steps": 0,
  "bodies": {
    "ball": {"com": [0, 0, 1], "velocity": [0, 0, 0], "rotation": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}
  },
  "min_distance": null,
  "min_volume_ratio": 0.5,
  "intersection_free": true,
  "newton_iterations": {"total": 0, "max_per_step": 0},
  "trace": [
  ]
}
]
}
)";
  EXPECT_EQ(report_text(two_scenes(), true), expected);
  EXPECT_EQ(report_text(two_scenes(), false).find("trace"), std::string::npos);
}

TEST(SceneReport, ScenesNamesAndFailuresWithQuotesBackslashesAndNewlinesSurviveARoundTrip) {
  const std::string path = "dir \"quoted\"\\sub\\\nline two.toml";
  const std::string failure = "t = 0.01 s: \"" + path + "\" \\ failed\nhere";
  const std::string body = "box \"b\"\\\n";
  BatchReport batch = two_scenes();
  batch.scenes[0].bodies[1].name = body;
  batch.scenes[1].scene = path;
  batch.scenes[1].failure = failure;
  const std::string text = report_text(batch, true);
  const nlohmann::json report = nlohmann::json::parse(text, nullptr, false);
  ASSERT_FALSE(report.is_discarded()) << text;
  EXPECT_EQ(report["scenes"][1]["scene"], path);
  EXPECT_EQ(report["scenes"][1]["failure"], failure);
  EXPECT_EQ(report["scenes"][0]["bodies"][body]["velocity"][2], -0.1);
  EXPECT_EQ(report["scenes"][0]["trace"][1]["com"][body][2], 0.05);
}

TEST(SceneReport, StaysValidJsonWhenAPathIsNotUtf8) {
  BatchReport batch = two_scenes();
  batch.scenes[0].scene = "caf\xe9.toml";  // Latin-1
  const std::string text = report_text(batch, false);
  const nlohmann::json report = nlohmann::json::parse(text, nullptr, false);
  ASSERT_FALSE(report.is_discarded()) << text;
  EXPECT_EQ(report["scenes"][0]["scene"], "caf\xef\xbf\xbd.toml");  // U+FFFD
}

}  // namespace
}  // namespace grip::scene
