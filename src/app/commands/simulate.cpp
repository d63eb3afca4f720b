// grip simulate SCENE.toml [--report out.json] [--trace]: one scene, run for its duration,
// with the JSON report on stdout or in a file.
#include <spdlog/spdlog.h>

#include <fstream>
#include <iostream>

#include "src/app/commands.hpp"
#include "src/config/config.hpp"
#include "src/scene/scene_run.hpp"

namespace grip::commands {

int simulate(const SimulateArgs& args) {
  scene::SceneFile file;
  try {
    file = scene::load_scene_file(args.scene);
  } catch (const config::ConfigError& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  const scene::SceneReport report = scene::run_scene(file, args.trace);
  if (args.report.empty()) {
    scene::write_json(std::cout, report, args.trace);
  } else {
    std::ofstream out(args.report);
    if (!out) {
      spdlog::error("{}: cannot write the report (does the folder exist?)", args.report);
      return 1;
    }
    scene::write_json(out, report, args.trace);
    spdlog::info("{}: {} steps, {} Newton iterations, {:.2f} s; report in {}", args.scene,
                 report.steps, report.newton_total, report.wall_seconds, args.report);
  }
  if (!report.ok) {
    spdlog::error("{}: simulation failed: {}", args.scene, report.failure);
    return 1;
  }
  return 0;
}

}  // namespace grip::commands
