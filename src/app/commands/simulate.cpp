// grip simulate SCENE.toml... [--threads T] [--report out.json] [--trace]: scenes run for their
// durations as one batch, with the JSON report on stdout or in a file.
#include <spdlog/spdlog.h>

#include <fstream>
#include <iostream>

#include "src/app/commands.hpp"
#include "src/config/config.hpp"
#include "src/scene/scene_run.hpp"

namespace grip::commands {

int simulate(const SimulateArgs& args) {
  std::vector<scene::SceneFile> files;
  try {
    for (const std::string& path : args.scenes) {
      files.push_back(scene::load_scene_file(path, args.max_tets));
    }
  } catch (const config::ConfigError& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  const scene::BatchReport report = scene::run_scenes(files, args.scenes, args.trace, args.threads);
  if (args.report.empty()) {
    scene::write_json(std::cout, report, args.trace);
  } else {
    std::ofstream out(args.report);
    if (!out) {
      spdlog::error("{}: cannot write the report (does the folder exist?)", args.report);
      return 1;
    }
    scene::write_json(out, report, args.trace);
    spdlog::info("{} scene(s) on {} thread(s) in {:.2f} s; report in {}", report.scenes.size(),
                 report.threads, report.wall_seconds, args.report);
  }
  int status = 0;
  for (const scene::SceneReport& scene : report.scenes) {
    if (scene.ok) {
      spdlog::info("{}: {} steps, {} Newton iterations", scene.scene, scene.steps,
                   scene.newton_total);
    } else {
      spdlog::error("{}: simulation failed: {}", scene.scene, scene.failure);
      status = 1;
    }
  }
  return status;
}

}  // namespace grip::commands
