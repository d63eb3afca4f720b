// grip simulate SCENE.toml... [--threads T] [--device D] [--report out.json] [--trace]: scenes
// run for their durations as one batch, with the JSON report on stdout or in a file.
#include <spdlog/spdlog.h>

#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "app/cli/command_line.hpp"
#include "app/cli/device_option.hpp"
#include "app/commands/commands.hpp"
#include "src/config/config.hpp"
#include "src/geometry/tetrahedralize.hpp"
#include "src/scene/scene_run.hpp"

namespace grip::commands {
namespace {

struct SimulateArgs {
  std::vector<std::string> scenes;
  int threads = 0;             // 0: all cores
  std::string device = "cpu";  // the engine: cpu, host (data-parallel) or cuda
  std::string report;          // JSON report file; stdout when empty
  bool trace = false;          // add each step's time and centres of mass to the report
  double max_tets = geometry::kMaxEstimatedTets;  // an FEM body of more tets is refused
};

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
  const scene::BatchReport report = scene::run_scenes(files, args.scenes, args.trace, args.threads,
                                                      solver::engine_device(args.device));
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

}  // namespace

void declare_simulate(cli::Command& root) {
  auto args = std::make_shared<SimulateArgs>();
  cli::Command simulate = root.subcommand(
      "simulate", "Simulate scene files (TOML) as one batch of environments and report");
  simulate.option("scenes", args->scenes, "Scene files (docs/scene-format.md)").required();
  simulate.option("--threads", args->threads, "Threads (default: all cores)")
      .check(cli::Check::count());
  simulate.option("--device", args->device, cli::device_help())
      .show_default()
      .check(cli::device_check());
  simulate.on_check([args] { cli::refuse_cuda_device(args->device); });
  simulate
      .option("--max-tets", args->max_tets,
              "Refuse an FEM body that would make more tets (estimated before meshing)")
      .show_default()
      .check(cli::Check::positive());
  simulate.option("--report", args->report, "Write the JSON report here (default: stdout)")
      .check(cli::Check::output_file());
  simulate.flag("--trace", args->trace, "Add per-step centres of mass to the report");
  simulate.on_run([args] { return grip::commands::simulate(*args); });
}

}  // namespace grip::commands
