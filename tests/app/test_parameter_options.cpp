// Every row of the parameter tables is a command-line option that checks its range as the job
// reader does (grip trial: [physics], [trial], [outputs]; grip synth: [synthesis] and d_hat),
// and the docs' tables are what `grip parameters` makes of the rows. A row missing from either
// fails here, naming it.
#include <gtest/gtest.h>

#include <string>

#include "src/config/parameter_table.hpp"
#include "src/scene/sim_parameters.hpp"
#include "src/synth/synthesis_settings.hpp"
#include "src/trial/trial_parameters.hpp"
#include "tests/app/run_grip.hpp"
#include "tests/config/parameter_samples.hpp"

namespace grip::testing {
namespace {

using config::testing::inside_value;
using config::testing::outside_value;

// `command` takes the row as an option: a value inside its range, and refuses one outside,
// naming the option.
template <class Group>
void check_option(const std::string& command, const config::Parameter<Group>& row,
                  const Group& defaults) {
  const std::string option = config::option_name(row.key);
  const GripRun inside =
      run_grip_checking_args(command + " " + option + " " + inside_value(row, defaults));
  EXPECT_EQ(inside.exit_code, 0) << command << " " << option << ": " << inside.err;
  const GripRun outside = run_grip_checking_args(command + " " + option + " " + outside_value(row));
  EXPECT_EQ(outside.exit_code, 2) << command << " " << option;
  EXPECT_NE(outside.err.find(option + ": must be"), std::string::npos) << outside.err;
}

TEST(ParameterOptions, GripTrialTakesEveryPhysicsAndTrialParameter) {
  const std::string trial = "trial --candidates c.txt";
  const grip::trial::TrialParameters defaults;
  for (const auto& row : scene::sim_parameter_table()) check_option(trial, row, defaults.sim);
  for (const auto& row : grip::trial::trial_parameter_table()) {
    check_option(trial, row, defaults);
  }
  EXPECT_EQ(run_grip_checking_args(trial + " --kappa auto").exit_code, 0);
  // Values that contradict each other are a usage error too.
  const GripRun contradiction = run_grip_checking_args(trial + " --phase-duration 0.001");
  EXPECT_EQ(contradiction.exit_code, 2);
  EXPECT_NE(contradiction.err.find("phase_duration"), std::string::npos) << contradiction.err;
}

TEST(ParameterOptions, GripSynthTakesEverySynthesisParameterAndDHat) {
  const std::string synth = "synth --object box --gripper fin-ray --count 1 --seed 1 --out c.txt";
  for (const auto& row : grip::synth::synthesis_parameter_table()) {
    check_option(synth, row, grip::synth::SynthesisSettings{});
  }
  for (const auto& row : scene::sim_parameter_table()) {
    if (row.key == "d_hat") check_option(synth, row, solver::SimParameters{});
  }
}

// The text between a doc's `<!-- grip parameters: NAME ...-->` line and the next
// `<!-- end of grip parameters -->`.
std::string doc_table(const std::string& doc, const std::string& name) {
  const std::string marker = "<!-- grip parameters: " + name + " ";
  const std::size_t at = doc.find(marker);
  if (at == std::string::npos) return "(no table " + name + ")";
  const std::size_t start = doc.find('\n', at) + 1;
  return doc.substr(start, doc.find("<!-- end of grip parameters -->", start) - start);
}

// `grip parameters`' table of one section.
std::string printed_table(const std::string& printed, const std::string& name) {
  const std::size_t at = printed.find("## [" + name + "]\n\n");
  if (at == std::string::npos) return "(not printed " + name + ")";
  const std::size_t start = at + name.size() + 7;
  const std::size_t end = printed.find("\n## ", start);
  return printed.substr(start, end == std::string::npos ? std::string::npos : end - start);
}

TEST(ParameterOptions, TheDocsTablesAreTheParameterTables) {
  const GripRun printed = run_grip("parameters");
  ASSERT_EQ(printed.exit_code, 0) << printed.err;
  const std::string job_format = slurp(std::string(GRIP_SOURCE_DIR) + "/docs/job-format.md");
  for (const std::string name : {"physics", "trial", "outputs", "synthesis"}) {
    EXPECT_EQ(doc_table(job_format, name), printed_table(printed.out, name))
        << "docs/job-format.md: " << name << ": run scripts/update-parameter-docs.py";
  }
  const std::string scene_format = slurp(std::string(GRIP_SOURCE_DIR) + "/docs/scene-format.md");
  EXPECT_EQ(doc_table(scene_format, "physics"), printed_table(printed.out, "physics"))
      << "docs/scene-format.md: run scripts/update-parameter-docs.py";
}

}  // namespace
}  // namespace grip::testing
