#pragma once
// Scene files (TOML, docs/scene-format.md) read strictly into a solver scene: simulation
// parameters, bodies with their shapes, materials, motion and pins, per-pair friction.
#include <filesystem>

#include "solver/scene.hpp"

namespace grip::scene {

struct SceneFile {
  solver::SceneDescription scene;
  double duration = 1.0;  // s: how long `grip simulate` runs the scene
};

// Throws config::ConfigError ("FILE:LINE: ...") for anything wrong in the file, including a
// mesh that cannot be read or tetrahedralized and an invalid body.
SceneFile load_scene_file(const std::filesystem::path& file);

}  // namespace grip::scene
