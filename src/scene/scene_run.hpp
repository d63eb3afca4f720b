#pragma once
// Runs a scene file's scene for its duration, checking the exact invariants after every step,
// and the JSON report `grip simulate` writes (docs/scene-format.md describes its fields).
#include <ostream>
#include <string>
#include <vector>

#include "src/scene/scene_file.hpp"

namespace grip::scene {

struct BodyReport {
  std::string name;
  Eigen::Vector3d com;
  Eigen::Vector3d velocity;
  Eigen::Matrix3d rotation;
};

struct TraceRow {
  double time = 0.0;
  std::vector<Eigen::Vector3d> com;  // per body, in scene order
};

struct SceneReport {
  bool ok = true;
  std::string failure;  // empty when ok
  int steps = 0;
  std::vector<BodyReport> bodies;
  double min_distance = std::numeric_limits<double>::infinity();  // over the run
  double min_volume_ratio = 1.0;
  bool intersection_free = true;
  int newton_total = 0;
  int newton_max_per_step = 0;
  double wall_seconds = 0.0;
  std::vector<TraceRow> trace;  // filled when asked for
};

SceneReport run_scene(const SceneFile& scene, bool trace);

void write_json(std::ostream& out, const SceneReport& report, bool trace);

}  // namespace grip::scene
