#pragma once
// The `grip` program's commands: each file of app/commands/ declares one command, its options
// beside the arguments they fill, and does its work. app/main.cpp declares them in the order
// `grip --help` lists them.
#include <string>

namespace grip::cli {
class Command;
}  // namespace grip::cli

namespace grip::commands {

void declare_farm(cli::Command& root);      // grip farm JOB.toml (farm.cpp)
void declare_trial(cli::Command& root);     // grip trial --candidates FILE (trial.cpp)
void declare_synth(cli::Command& root);     // grip synth --object ... --out FILE (synth.cpp)
void declare_simulate(cli::Command& root);  // grip simulate SCENE.toml... (simulate.cpp)
void declare_inspect(cli::Command& root);   // grip inspect DATASET.h5 (inspect.cpp)
// grip export --layout grip DATASET.h5 DIR (export.cpp)
void declare_export(cli::Command& root);
// grip parameters: every parameter of job and scene files (parameters.cpp).
void declare_parameters_command(cli::Command& root);
// The `asset` group's commands: prepare (asset_prepare.cpp) and gallery (asset_gallery.cpp).
void declare_asset_prepare(cli::Command& asset);
void declare_asset_gallery(cli::Command& asset);

// The Markdown tables grip parameters prints, one per section of a job file.
std::string parameter_tables();

// A dataset's provenance and summary on stdout: grip inspect's work, and grip farm's last words.
// The exit code: 1 when committed rows do not match their checksums.
int inspect(const std::string& dataset, bool show_job);

}  // namespace grip::commands
