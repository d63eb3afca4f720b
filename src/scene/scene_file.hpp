#pragma once
// Scene files (TOML, docs/scene-format.md) read strictly into a solver scene: simulation
// parameters, bodies with their shapes, materials, motion and pins, per-pair friction.
#include <cmath>
#include <cstdint>
#include <filesystem>

#include "solver/scene/scene.hpp"
#include "src/geometry/tetrahedralize.hpp"

namespace grip::scene {

// The most steps a scene file may ask for (duration / dt): more would run for days.
inline constexpr std::int64_t kMaxSceneSteps = 10'000'000;

struct SceneFile {
  solver::SceneDescription scene;
  double duration = 1.0;  // s: how long `grip simulate` runs the scene

  // The steps `grip simulate` runs: round(duration / dt), from 1 to kMaxSceneSteps in a file
  // load_scene_file read.
  std::int64_t steps() const { return std::llround(duration / scene.sim.dt); }
};

// Throws config::ConfigError ("FILE:LINE: ...") for anything wrong in the file, including a
// mesh that cannot be read or tetrahedralized, an FEM resolution that would make a body of more
// than `max_tets` tets (estimated before meshing; `grip simulate --max-tets`), a duration of no
// step or of more than kMaxSceneSteps, and an invalid body.
SceneFile load_scene_file(const std::filesystem::path& file,
                          double max_tets = geometry::kMaxEstimatedTets);

}  // namespace grip::scene
