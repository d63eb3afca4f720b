// grip parameters: every setting a job file's [physics], [trial], [outputs] and [synthesis]
// tables take (a scene file's [sim] takes [physics]'), with its default, unit, allowed values
// and meaning, as Markdown tables: the same tables docs/job-format.md and docs/scene-format.md
// hold, made from the parameter tables the readers use.
#include <cstdio>
#include <memory>
#include <string>

#include "app/cli/command_line.hpp"
#include "app/commands/commands.hpp"
#include "src/config/parameter_table.hpp"
#include "src/scene/sim_parameters.hpp"
#include "src/synth/synthesis_settings.hpp"
#include "src/trial/trial_parameters.hpp"

namespace grip::commands {

std::string parameter_tables() {
  const trial::TrialParameters trial;
  return "## [physics]\n\n" + config::markdown_table(scene::sim_parameter_table(), trial.sim) +
         "\n## [trial]\n\n" + config::markdown_table(trial::trial_parameter_table(), trial) +
         "\n## [outputs]\n\n" +
         config::markdown_table(trial::trial_parameter_table(), trial, "outputs") +
         "\n## [synthesis]\n\n" +
         config::markdown_table(synth::synthesis_parameter_table(), synth::SynthesisSettings{});
}

void declare_parameters_command(cli::Command& root) {
  cli::Command parameters = root.subcommand(
      "parameters",
      "Print every job and scene parameter: default, unit, allowed values, meaning (Markdown)");
  parameters.on_run([] {
    std::fputs(parameter_tables().c_str(), stdout);
    return 0;
  });
}

}  // namespace grip::commands
