#include "farm/job.hpp"

#include <glob.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "src/config/config.hpp"
#include "src/config/parameter_table.hpp"
#include "src/grippers/gripper_description.hpp"
#include "src/grippers/number_text.hpp"
#include "src/objects/object_library.hpp"
#include "src/scene/sim_parameters.hpp"

namespace grip::farm {
namespace {

using config::Table;

// The [outputs] table's section of the trial parameter table: the frame counts.
constexpr std::string_view kOutputs = "outputs";

double positive(const Table& table, std::string_view key, double fallback) {
  const double value = table.number_or(key, fallback);
  if (!(value > 0)) table.fail(key, "must be positive");
  return value;
}

int positive_integer(const Table& table, std::string_view key, int fallback) {
  const std::int64_t value = table.integer_or(key, fallback);
  if (value < 1 || value > 1'000'000'000) table.fail(key, "must be a positive integer");
  return static_cast<int>(value);
}

// [min, max] with 0 < min <= max (or 0 <= min for a coefficient that may vanish).
void read_range(const Table& table, std::string_view key, double& min, double& max,
                bool zero_allowed = false) {
  if (!table.has(key)) return;
  const std::vector<double> range = table.numbers(key);
  if (range.size() != 2 || range[0] > range[1] || range[0] < 0 ||
      (!zero_allowed && range[0] == 0)) {
    table.fail(key, zero_allowed ? "must be [min, max] with 0 <= min <= max"
                                 : "must be [min, max] with 0 < min <= max");
  }
  min = range[0];
  max = range[1];
}

// The mesh files a path or glob names, relative to the job file's folder, sorted.
std::vector<std::filesystem::path> resolve_meshes(const Table& group, const std::string& pattern,
                                                  const std::filesystem::path& job_dir) {
  const std::filesystem::path full = std::filesystem::path(pattern).is_absolute()
                                         ? std::filesystem::path(pattern)
                                         : job_dir / pattern;
  glob_t matches{};
  const int status = ::glob(full.c_str(), 0, nullptr, &matches);
  std::vector<std::filesystem::path> files;
  if (status == 0) {
    for (std::size_t i = 0; i < matches.gl_pathc; ++i) {
      if (std::filesystem::is_regular_file(matches.gl_pathv[i]))
        files.emplace_back(matches.gl_pathv[i]);
    }
  }
  ::globfree(&matches);
  if (files.empty()) {
    group.fail("mesh", "'" + full.string() +
                           "' matches no file; paths are relative to the job file's folder");
  }
  return files;
}

ObjectGroup read_object_group(const Table& t, const std::filesystem::path& job_dir) {
  t.allow({"category", "mesh", "count", "soft", "tet_edge", "tet_growth", "tets_across", "scale",
           "randomize", "density", "youngs", "poisson", "friction"});
  ObjectGroup group;
  if (t.has("category") == t.has("mesh")) {
    t.fail(t.has("mesh") ? "mesh" : "category",
           "give exactly one of 'category' (a procedural shape) and 'mesh' (a file or glob)");
  }
  if (t.has("category")) {
    group.category = t.string("category");
    try {
      objects::parse_object_category(group.category);
    } catch (const std::invalid_argument& error) {
      t.fail("category", error.what());
    }
    group.count = positive_integer(t, "count", 1);
    if (t.has("scale")) t.fail("scale", "applies to mesh files only; use [randomization] scale");
  } else {
    if (t.has("tets_across")) {
      t.fail("tets_across", "applies to categories only; a mesh file's tets follow tet_edge");
    }
    group.meshes = resolve_meshes(t, t.string("mesh"), job_dir);
    if (t.has("count"))
      t.fail("count", "applies to categories only; a mesh entry takes every file it names");
    group.mesh_scale = positive(t, "scale", 1.0);
  }
  group.soft = t.boolean_or("soft", false);
  group.tet_edge = positive(t, "tet_edge", group.tet_edge);
  group.tet_edge_at = t.location("tet_edge");
  group.tet_growth = t.number_or("tet_growth", group.tet_growth);
  if (!(group.tet_growth >= 0 && group.tet_growth <= geometry::kMaxInteriorGrowth)) {
    t.fail("tet_growth", "must lie in [0, " + grippers::number_text(geometry::kMaxInteriorGrowth) +
                             "] (0: tets of tet_edge throughout)");
  }
  group.tets_across = t.number_or("tets_across", group.tets_across);
  if (!(group.tets_across >= objects::kMinTetsAcross &&
        group.tets_across <= objects::kMaxTetsAcross)) {
    t.fail("tets_across",
           "must lie in [" + grippers::number_text(objects::kMinTetsAcross) + ", " +
               grippers::number_text(objects::kMaxTetsAcross) +
               "] (tet edges across a category's thinnest part; 1 leaves slivers in curved walls)");
  }
  group.randomize = t.boolean_or("randomize", true);
  for (const char* key : {"density", "youngs", "poisson", "friction"}) {
    if (group.randomize && t.has(key)) {
      t.fail(key, "is drawn from [randomization] unless the entry sets randomize = false");
    }
  }
  objects::ObjectMaterial& m = group.material;
  m.density = positive(t, "density", m.density);
  m.youngs_modulus = positive(t, "youngs", m.youngs_modulus);
  m.poisson_ratio = t.number_or("poisson", m.poisson_ratio);
  if (!(m.poisson_ratio >= 0 && m.poisson_ratio < 0.5)) t.fail("poisson", "must lie in [0, 0.5)");
  m.friction = t.number_or("friction", m.friction);
  if (!(m.friction >= 0)) t.fail("friction", "must be non-negative");
  return group;
}

GripperSetting read_gripper(const Table& t, const std::filesystem::path& job_dir) {
  t.allow({"name", "description", "bimanual", "candidates"});
  GripperSetting setting;
  if (t.has("name") == t.has("description")) {
    t.fail(t.has("name") ? "description" : "name",
           "a gripper is a built-in one's name or a description file, one of them");
  }
  if (t.has("name")) {
    const std::string name = t.string("name");
    const grippers::GripperType* type = grippers::find_gripper_type(name);
    if (!type) {
      std::string names;
      for (const std::string& known : grippers::gripper_names()) {
        names += (names.empty() ? "\"" : ", \"") + known + "\"";
      }
      t.fail("name", "is \"" + name + "\" but must be one of " + names +
                         " (or give a soft gripper's description file as description)");
    }
    setting.type = *type;
  } else {
    const std::filesystem::path file = job_dir / t.string("description");
    if (!grippers::is_gripper_description(file)) {
      t.fail("description", "names '" + file.string() +
                                "', not a gripper description file (*.toml; docs/assets.md)");
    }
    if (!std::filesystem::is_regular_file(file)) {
      t.fail("description", "names '" + file.string() +
                                "', which does not exist; paths are relative to the job file's "
                                "folder");
    }
    setting.type = grippers::resolve_gripper(file.string());
  }
  setting.bimanual = t.boolean_or("bimanual", false);
  setting.candidates = positive_integer(t, "candidates", setting.candidates);
  return setting;
}

// A setting (gripper and bimanual) given twice would be two gripper records of the same
// grippers whose candidates differ only by their synthesis stream: refused on the second entry.
// Grippers are told apart by name, which the dataset records.
void check_distinct_settings(const std::vector<Table>& tables,
                             const std::vector<GripperSetting>& settings) {
  for (std::size_t b = 1; b < settings.size(); ++b) {
    for (std::size_t a = 0; a < b; ++a) {
      if (settings[a].type.name != settings[b].type.name ||
          settings[a].bimanual != settings[b].bimanual) {
        continue;
      }
      const std::string which = std::string(settings[b].bimanual ? "bimanual " : "unimanual ") +
                                "'" + settings[b].type.name + "'";
      const std::string key = tables[b].has("name") ? "name" : "description";
      tables[b].fail(tables[b].has("bimanual") ? "bimanual" : key,
                     "repeats the " + which + " setting of the entry at " +
                         tables[a].location(tables[a].has("name") ? "name" : "description") +
                         "; give each setting once and raise its candidates instead");
    }
  }
}

void read_randomization(const Table& t, objects::RandomizationRanges& r) {
  t.allow({"scale", "youngs", "poisson", "density", "friction"});
  read_range(t, "scale", r.scale_min, r.scale_max);
  read_range(t, "youngs", r.youngs_modulus_min, r.youngs_modulus_max);
  read_range(t, "poisson", r.poisson_ratio_min, r.poisson_ratio_max, true);
  if (r.poisson_ratio_max >= 0.5) t.fail("poisson", "must stay below 0.5");
  read_range(t, "density", r.density_min, r.density_max);
  read_range(t, "friction", r.friction_min, r.friction_max, true);
}

void read_trial(const Table& t, trial::TrialParameters& p) {
  t.allow(config::parameter_keys(trial::trial_parameter_table()));
  config::read_parameters(t, trial::trial_parameter_table(), p);
  if (p.metric_samples > trial::kMaxMetricSamples) {
    t.fail("metric_samples", "is " + std::to_string(p.metric_samples) +
                                 " surface points per gripper, more than the " +
                                 std::to_string(trial::kMaxMetricSamples) +
                                 " a trial may hold (24 bytes each, per hand); sample fewer");
  }
}

// A tiny dt (or long phases) would make a trial of more steps than an int counts, or run for
// days: refused on the key that set it.
void check_trial_steps(const trial::TrialParameters& p, const std::optional<Table>& physics,
                       const std::optional<Table>& trial_table) {
  const double steps = trial::max_trial_steps(p);
  if (steps <= static_cast<double>(trial::kMaxTrialSteps)) return;
  char message[256];
  std::snprintf(message, sizeof message,
                "makes a trial of up to %.3g steps (settle_max_steps + 6 x (phase_duration + "
                "rest_duration) / dt), more than the %lld allowed; use a larger [physics] dt or "
                "a shorter [trial] phase_duration or rest_duration",
                steps, static_cast<long long>(trial::kMaxTrialSteps));
  if (physics && physics->has("dt")) physics->fail("dt", message);
  for (const char* key : {"phase_duration", "rest_duration"}) {
    if (trial_table && trial_table->has(key)) trial_table->fail(key, message);
  }
  if (trial_table) trial_table->fail("settle_max_steps", message);
}

// Values that contradict each other, refused on the key that set them: a trial that could
// never count as settled, a gravity phase shorter than one step.
void check_trial_consistency(const trial::TrialParameters& p, const std::optional<Table>& physics,
                             const std::optional<Table>& trial_table) {
  const std::string steady = std::to_string(p.settle_steps);
  const std::string most = std::to_string(p.settle_max_steps);
  if (p.settle_max_steps < p.settle_steps && trial_table) {
    const std::string why =
        ", so no trial could ever settle; make settle_max_steps at least "
        "settle_steps";
    if (trial_table->has("settle_max_steps")) {
      trial_table->fail("settle_max_steps",
                        "= " + most + " is fewer than settle_steps = " + steady + why);
    }
    trial_table->fail("settle_steps",
                      "= " + steady + " is more than settle_max_steps = " + most + why);
  }
  if (p.phase_duration < p.sim.dt) {
    char message[256];
    if (trial_table && trial_table->has("phase_duration")) {
      std::snprintf(message, sizeof message,
                    "= %g s is shorter than one step ([physics] dt = %g s); make phase_duration at "
                    "least dt",
                    p.phase_duration, p.sim.dt);
      trial_table->fail("phase_duration", message);
    }
    if (physics && physics->has("dt")) {
      std::snprintf(message, sizeof message,
                    "= %g s is longer than a gravity phase ([trial] phase_duration = %g s); make "
                    "dt at most phase_duration",
                    p.sim.dt, p.phase_duration);
      physics->fail("dt", message);
    }
  }
}

void read_outputs(const Table& t, Job& job) {
  t.allow(config::parameter_keys(trial::trial_parameter_table(), kOutputs),
          {"frames", "stress", "full_trials"});
  job.record_frames = t.boolean_or("frames", job.record_frames);
  job.record_stress = t.boolean_or("stress", job.record_stress);
  job.full_trials = t.boolean_or("full_trials", job.full_trials);
  config::read_parameters(t, trial::trial_parameter_table(), job.trial, kOutputs);
  if (job.trial.validation_frames % 6 != 0) {
    t.fail("validation_frames", "must be a multiple of 6 (one share per gravity axis)");
  }
  if (job.trial.closing_frames + static_cast<double>(job.trial.validation_frames) >
      trial::kMaxTrialFrames) {
    const bool closing =
        t.has("closing_frames") &&
        (!t.has("validation_frames") || job.trial.closing_frames > job.trial.validation_frames);
    t.fail(closing ? "closing_frames" : "validation_frames",
           "makes closing_frames + validation_frames more than the " +
               std::to_string(trial::kMaxTrialFrames) +
               " frames a trial may record; record fewer frames");
  }
}

void read_farm(const Table& t, Job& job) {
  t.allow({"batch", "max_candidates", "max_tets", "petsc_group_ranks", "petsc_groups",
           "petsc_min_dofs", "petsc_min_factor_mib"});
  const std::int64_t size = t.integer_or("batch", 0);
  if (size < 0 || size > 100000) t.fail("batch", "must be 0 (automatic) or a positive count");
  job.work_unit_size = static_cast<int>(size);
  const std::int64_t most = t.integer_or("max_candidates", Job::kDefaultMaxCandidates);
  // The dataset counts candidates in 32 bits (io::DatasetLayout).
  if (most < 1 || most > std::numeric_limits<std::uint32_t>::max()) {
    t.fail("max_candidates", "must be a count from 1 to 4294967295");
  }
  job.max_candidates = static_cast<std::uint64_t>(most);
  job.max_tets = t.number_or("max_tets", job.max_tets);
  if (!(job.max_tets >= 1)) t.fail("max_tets", "must be a count of at least 1");
  PetscGroupSetting& petsc = job.petsc;
  petsc.group_ranks = t.count_or("petsc_group_ranks", 0, 0, 1 << 20);
  petsc.groups = t.count_or("petsc_groups", 1, 1, 1 << 20);
  if (t.has("petsc_min_dofs")) petsc.min_dofs = t.count_or("petsc_min_dofs", 1, 1, 2'000'000'000);
  petsc.min_factor_mib =
      t.number_or("petsc_min_factor_mib", PetscGroupSetting::kDefaultMinFactorMib);
  if (!(petsc.min_factor_mib > 0.0 && petsc.min_factor_mib <= 1e9)) {
    t.fail("petsc_min_factor_mib", "must be a size in MiB, more than 0 and at most 1e9");
  }
  if (petsc.group_ranks == 0) {
    for (const char* key : {"petsc_groups", "petsc_min_dofs", "petsc_min_factor_mib"}) {
      if (t.has(key))
        t.fail(key, "needs petsc_group_ranks (the ranks of a PETSc group, 1 or more)");
    }
  }
  if (static_cast<std::int64_t>(petsc.group_ranks) * petsc.groups > (1 << 20)) {
    t.fail("petsc_groups", "times petsc_group_ranks must be at most 1048576 ranks");
  }
  petsc.location = t.location("petsc_group_ranks");
}

// A job of more candidates than [farm] max_candidates is refused before planning, which holds
// every candidate in memory on every rank and would otherwise run for days before a trial. It is
// refused on the key that made it large (max_candidates if set, else the largest [[grippers]]
// candidates, else the largest [[objects]] count), saying what it would need.
void check_candidate_count(const Job& job, const Table& root,
                           const std::vector<Table>& gripper_tables,
                           const std::optional<Table>& farm_table) {
  const std::uint64_t count = job.candidate_count();
  if (count <= job.max_candidates) return;
  const auto objects = static_cast<double>(job.object_count());
  double per_object = 0, cpu_seconds = 0;
  std::size_t largest_group = 0, largest_gripper = 0;
  for (std::size_t i = 0; i < job.objects.size(); ++i) {
    if (job.objects[i].object_count() > job.objects[largest_group].object_count()) {
      largest_group = i;
    }
  }
  for (std::size_t g = 0; g < job.grippers.size(); ++g) {
    const GripperSetting& setting = job.grippers[g];
    per_object += setting.candidates;
    cpu_seconds +=
        objects * setting.candidates * setting.type.trial_cpu_seconds * (setting.bimanual ? 2 : 1);
    if (setting.candidates > job.grippers[largest_gripper].candidates) largest_gripper = g;
  }
  char message[512];
  std::snprintf(message, sizeof message,
                "makes %.4g candidates (%.4g object%s x %.4g candidates per object), more than "
                "the job's limit of %llu ([farm] max_candidates): planning would hold them all "
                "in memory on every rank, and their trials would take at least %.3g CPU hours; "
                "plan fewer, or raise [farm] max_candidates if that is meant",
                static_cast<double>(count), objects, objects == 1 ? "" : "s", per_object,
                static_cast<unsigned long long>(job.max_candidates), cpu_seconds / 3600);
  if (farm_table && farm_table->has("max_candidates")) farm_table->fail("max_candidates", message);
  if (job.grippers[largest_gripper].candidates > 1) {
    gripper_tables[largest_gripper].fail("candidates", message);
  }
  const std::vector<Table> object_tables = root.tables("objects");
  object_tables[largest_group].fail(job.objects[largest_group].category.empty() ? "mesh" : "count",
                                    message);
}

}  // namespace

std::uint64_t Job::object_count() const {
  std::uint64_t count = 0;
  for (const ObjectGroup& group : objects) count += group.object_count();
  return count;
}

std::uint64_t Job::candidate_count() const {
  const std::uint64_t objects_in_job = object_count();
  std::uint64_t per_object = 0, count = 0;
  for (const GripperSetting& setting : grippers) {
    per_object += static_cast<std::uint64_t>(setting.candidates);
  }
  // Each sum stays far below 2^64 (counts of at most 1e9 per entry); the product may not.
  if (__builtin_mul_overflow(objects_in_job, per_object, &count)) {
    return std::numeric_limits<std::uint64_t>::max();
  }
  return count;
}

Job parse_job(std::string text, const std::filesystem::path& file) {
  const config::Document document = config::Document::parse(std::move(text), file);
  const Table root = document.root();
  root.allow({"job", "objects", "grippers", "randomization", "physics", "trial", "synthesis",
              "outputs", "farm"});
  Job job;
  job.file = file;
  job.text = document.text();

  const Table head = root.table("job");
  head.allow({"name", "seed", "output"});
  job.name = head.string("name");
  if (job.name.empty() || job.name.find_first_of("/\\ ") != std::string::npos) {
    head.fail("name", "must be a non-empty word without '/' or spaces (it names the output)");
  }
  const std::int64_t seed = head.integer_or("seed", 0);
  if (seed < 0) head.fail("seed", "must be non-negative");
  job.seed = static_cast<std::uint64_t>(seed);
  job.output = head.string_or("output", "out/" + job.name + "/dataset.h5");

  const std::filesystem::path job_dir = file.parent_path().empty() ? "." : file.parent_path();
  for (const Table& group : root.tables("objects"))
    job.objects.push_back(read_object_group(group, job_dir));
  if (job.objects.empty()) root.fail("objects", "the job needs at least one [[objects]] entry");
  const std::vector<Table> gripper_tables = root.tables("grippers");
  for (const Table& gripper : gripper_tables) {
    job.grippers.push_back(read_gripper(gripper, job_dir));
  }
  check_distinct_settings(gripper_tables, job.grippers);
  if (job.grippers.empty()) root.fail("grippers", "the job needs at least one [[grippers]] entry");

  if (auto t = root.optional_table("randomization")) read_randomization(*t, job.randomization);
  const auto physics = root.optional_table("physics");
  if (physics) {
    physics->allow(config::parameter_keys(scene::sim_parameter_table()));
    scene::read_sim_parameters(*physics, job.trial.sim);
  }
  const auto trial_table = root.optional_table("trial");
  if (trial_table) read_trial(*trial_table, job.trial);
  check_trial_steps(job.trial, physics, trial_table);
  check_trial_consistency(job.trial, physics, trial_table);
  if (auto t = root.optional_table("synthesis")) {
    t->allow(config::parameter_keys(synth::synthesis_parameter_table()));
    config::read_parameters(*t, synth::synthesis_parameter_table(), job.synthesis);
  }
  if (auto t = root.optional_table("outputs")) read_outputs(*t, job);
  const auto farm_table = root.optional_table("farm");
  if (farm_table) read_farm(*farm_table, job);
  check_candidate_count(job, root, gripper_tables, farm_table);
  // Whatever the trial would still refuse, refused now rather than mid-plan on one rank.
  try {
    trial::validate(job.trial);
  } catch (const std::invalid_argument& e) {
    throw config::ConfigError(file.string() + ": " + e.what());
  }
  return job;
}

std::string read_job_text(const std::filesystem::path& file) {
  if (std::filesystem::is_directory(file)) {
    throw config::ConfigError(file.string() + ": is a directory, not a job file");
  }
  std::ifstream in(file, std::ios::binary);
  if (!in) throw config::ConfigError(file.string() + ": cannot read the job file");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

Job load_job(const std::filesystem::path& file) { return parse_job(read_job_text(file), file); }

std::vector<io::Parameter> resolved_parameters(const Job& job) {
  std::vector<io::Parameter> out;
  const auto add = [&out](std::string_view section, const auto& rows, const auto& values) {
    for (const auto& row : rows) {
      const std::string_view group = row.section.empty() ? section : row.section;
      out.push_back(
          {std::string(group) + "." + std::string(row.key), config::value_text(row, values)});
    }
  };
  add("physics", scene::sim_parameter_table(), job.trial.sim);
  add("trial", trial::trial_parameter_table(), job.trial);
  add("synthesis", synth::synthesis_parameter_table(), job.synthesis);
  return out;
}

}  // namespace grip::farm
