#pragma once
// Runs scene files' scenes for their durations as one batch, checking the exact invariants
// after every step, and the JSON report `grip simulate` writes (docs/scene-format.md describes
// its fields).
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "solver/batch/engines.hpp"
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
  std::string scene;  // the scene file
  bool ok = true;
  std::string failure;  // empty when ok
  std::int64_t steps = 0;
  std::vector<BodyReport> bodies;
  double min_distance = std::numeric_limits<double>::infinity();  // over the run
  double min_volume_ratio = 1.0;
  bool intersection_free = true;
  std::int64_t newton_total = 0;
  int newton_max_per_step = 0;
  std::vector<TraceRow> trace;  // filled when asked for
};

struct BatchReport {
  int threads = 1;
  double wall_seconds = 0.0;
  std::vector<SceneReport> scenes;  // in the order given
};

// Steps every scene in one batch of `device`'s engine (solver/batch/engines.hpp) on `threads`
// threads (0: all cores) until each has run for its duration or failed, checking every step for
// intersections exactly. Each scene's result equals a run of it alone on that engine.
BatchReport run_scenes(const std::vector<SceneFile>& files, const std::vector<std::string>& names,
                       bool trace, int threads,
                       solver::EngineDevice device = solver::EngineDevice::kCpu);

void write_json(std::ostream& out, const BatchReport& report, bool trace);

}  // namespace grip::scene
