// Every row of the parameter tables a job file takes ([physics], [trial], [outputs],
// [synthesis]) reaches every place derived from it: the job reader reads it, its range check
// refuses a value outside, and the dataset's provenance records it. A row missing from any of
// them fails here, naming it.
#include <gtest/gtest.h>

#include <string>

#include "farm/job.hpp"
#include "src/config/parameter_table.hpp"
#include "src/scene/sim_parameters.hpp"
#include "src/synth/synthesis_settings.hpp"
#include "src/trial/trial_parameters.hpp"
#include "tests/config/parameter_samples.hpp"

namespace grip::farm {
namespace {

using config::testing::field_value;
using config::testing::inside_value;
using config::testing::outside_value;

const std::string kJob =
    "[job]\nname = \"t\"\n[[objects]]\ncategory = \"cylinder\"\n[[grippers]]\n"
    "name = \"parallel-jaw\"\n";

// The job with `key = value` in its table `section`.
std::string job_with(std::string_view section, std::string_view key, const std::string& value) {
  return kJob + "[" + std::string(section) + "]\n" + std::string(key) + " = " + value + "\n";
}

std::string error_of(const std::string& text) {
  try {
    parse_job(text, "job.toml");
  } catch (const config::ConfigError& e) {
    return e.what();
  }
  return "";
}

std::string provenance_value(const Job& job, const std::string& key) {
  for (const io::Parameter& p : resolved_parameters(job)) {
    if (p.key == key) return p.value;
  }
  return "(not recorded)";
}

// Each row of `rows`, read from its section of a job file into the field `group_of(job)` holds.
template <class Group, class GroupOf>
void check_rows(config::ParameterTable<Group> rows, std::string_view section, const Group& defaults,
                GroupOf group_of) {
  for (const config::Parameter<Group>& row : rows) {
    const std::string_view table = row.section.empty() ? section : row.section;
    const std::string name = std::string(table) + "." + std::string(row.key);
    const std::string value = inside_value(row, defaults);
    const Job job = parse_job(job_with(table, row.key, value), "job.toml");
    EXPECT_EQ(config::number_text(field_value(row, group_of(job))),
              config::number_text(std::stod(value)))
        << name << " is not read";
    EXPECT_EQ(provenance_value(job, name), value) << name << " is not in the provenance";
    const std::string refused = error_of(job_with(table, row.key, outside_value(row)));
    EXPECT_NE(refused.find("key '" + name + "' must"), std::string::npos)
        << name << " = " << outside_value(row) << ": " << refused;
  }
}

TEST(JobParameters, EveryPhysicsTrialAndSynthesisParameterIsReadCheckedAndRecorded) {
  const trial::TrialParameters trial;
  check_rows(scene::sim_parameter_table(), "physics", trial.sim,
             [](const Job& job) -> const solver::SimParameters& { return job.trial.sim; });
  check_rows(trial::trial_parameter_table(), "trial", trial,
             [](const Job& job) -> const trial::TrialParameters& { return job.trial; });
  check_rows(synth::synthesis_parameter_table(), "synthesis", synth::SynthesisSettings{},
             [](const Job& job) -> const synth::SynthesisSettings& { return job.synthesis; });
}

TEST(JobParameters, KappaTakesAutoAndTheProvenanceSaysSo) {
  const Job job = parse_job(job_with("physics", "kappa", "\"auto\""), "job.toml");
  EXPECT_TRUE(job.trial.sim.adaptive_kappa);
  EXPECT_EQ(provenance_value(job, "physics.kappa"), "auto");
  EXPECT_NE(error_of(job_with("physics", "kappa", "\"fast\"")).find("physics.kappa"),
            std::string::npos);
}

TEST(JobParameters, TheProvenanceListsEveryRowOnce) {
  const Job job = parse_job(kJob, "job.toml");
  const std::size_t rows = scene::sim_parameter_table().size() +
                           trial::trial_parameter_table().size() +
                           synth::synthesis_parameter_table().size();
  EXPECT_EQ(resolved_parameters(job).size(), rows);
}

}  // namespace
}  // namespace grip::farm
