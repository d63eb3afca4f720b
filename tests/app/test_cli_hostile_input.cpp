// Hostile input as a user may give it: scene durations and FEM resolutions past the limits,
// candidate files with numbers that are not finite or far away or counts they do not hold, trial
// and synth options out of their range, job files past the trial's limits, paths with quotes and
// backslashes, a body inside another, output paths that cannot be written, folders given as
// input files, contradictory job values, a bad job under mpirun. Each is refused in one line
// naming the file and key or the option, with a non-zero exit, before anything runs; a path
// round-trips through the reports.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/app/run_grip.hpp"

namespace grip::testing {
namespace {

namespace fs = std::filesystem;

// Per process: ctest runs each test case as its own process, possibly in parallel.
fs::path scratch(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("grip_hostile_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

const std::string kBox =
    "[[body]]\nname = \"b\"\ntype = \"affine\"\nshape = \"box\"\nsize = [0.1, 0.1, 0.1]\n";

// `grip simulate` on a scene with this text: refused in one line holding `expected`, exit 1.
void expect_scene_refused(const fs::path& dir, const std::string& text,
                          const std::string& expected) {
  const fs::path scene = dir / "scene.toml";
  std::ofstream(scene) << text;
  const GripRun run = run_grip("simulate " + quoted(scene));
  EXPECT_EQ(run.exit_code, 1) << text << run.err;
  EXPECT_EQ(count_lines(run.err), 1) << run.err;
  EXPECT_NE(run.err.find(expected), std::string::npos) << run.err;
  EXPECT_TRUE(run.out.empty()) << run.out;
}

// An OBJ cube of half-width `half`, centred on the origin, faces outward.
void write_cube(const fs::path& path, double half) {
  std::ofstream obj(path);
  for (const double x : {-half, half})
    for (const double y : {-half, half})
      for (const double z : {-half, half}) obj << "v " << x << ' ' << y << ' ' << z << '\n';
  obj << "f 1 2 4\nf 1 4 3\nf 5 7 8\nf 5 8 6\nf 1 5 6\nf 1 6 2\n"
         "f 3 4 8\nf 3 8 7\nf 1 3 7\nf 1 7 5\nf 2 6 8\nf 2 8 4\n";
}

TEST(HostileInput, SceneDurationsOfNoStepOrTooManyStepsAreRefused) {
  const fs::path dir = scratch("steps");
  // 2^32 steps once wrapped to 0 steps and "ok"; 2^31 to a run that never ended.
  expect_scene_refused(dir, "[sim]\ndt = 1\nduration = 4294967296\n" + kBox,
                       "scene.toml:3: key 'sim.duration' makes 4.29e+09 steps (duration "
                       "4.29497e+09 s, dt 1 s), more than the 10000000 a scene may run; shorten "
                       "duration or raise dt");
  expect_scene_refused(dir, "[sim]\ndt = 1\nduration = 2147483648\n" + kBox,
                       "key 'sim.duration' makes 2.15e+09 steps");
  expect_scene_refused(dir, "[sim]\ndt = 1e-300\n" + kBox,
                       "scene.toml:2: key 'sim.dt' makes 1e+300 steps");
  expect_scene_refused(dir, "[sim]\ndt = 0.01\nduration = 0.001\n" + kBox,
                       "key 'sim.duration' makes no step (duration 0.001 s, dt 0.01 s); make "
                       "duration at least dt");
  fs::remove_all(dir);
}

TEST(HostileInput, CountsPast32BitsAreRefusedNotWrapped) {
  const fs::path dir = scratch("counts");
  // 2^32 + 1 Newton iterations once wrapped to 1, and ran.
  expect_scene_refused(dir, "[sim]\nmax_newton_iters = 4294967297\n" + kBox,
                       "scene.toml:2: key 'sim.max_newton_iters' must be a whole number from 1 "
                       "to 100000, not 4294967297");
  expect_scene_refused(dir, "[sim]\nfriction_lag_iterations = 4294967297\n" + kBox,
                       "key 'sim.friction_lag_iterations' must be a whole number from 1 to 100");
  expect_scene_refused(dir, "[sim]\nprojected_iterations = -1\n" + kBox,
                       "key 'sim.projected_iterations' must be a whole number from 0 to 100000");
  expect_scene_refused(dir, "[sim]\nreuse_iterations = 1001\n" + kBox,
                       "key 'sim.reuse_iterations' must be a whole number from 0 to 1000");
  expect_scene_refused(dir, "[sim]\nreuse_tolerance = 1\n" + kBox,
                       "key 'sim.reuse_tolerance' must lie strictly between 0 and 1");
  const std::string sphere =
      "[[body]]\nname = \"s\"\ntype = \"affine\"\nshape = \"sphere\"\nradius = 0.05\n";
  // 2^32 + 3 segments wrapped to 3 (refused as "at least 6"); 1e8 built for ever.
  expect_scene_refused(dir, sphere + "segments = 4294967299\n",
                       "scene.toml:6: key 'body[0].segments' must be a whole number from 6 to "
                       "1024, not 4294967299");
  expect_scene_refused(dir, sphere + "segments = 100000000\n", "not 100000000");
  // The solver settings the format lists are read (two were once refused as unknown keys).
  const fs::path scene = dir / "scene.toml";
  std::ofstream(scene) << "[sim]\nduration = 0.02\nprojected_iterations = 5\n"
                          "max_step_halvings = 2\nreuse_iterations = 0\nreuse_tolerance = 1e-6\n"
                       << kBox;
  const GripRun run = run_grip("simulate " + quoted(scene));
  EXPECT_EQ(run.exit_code, 0) << run.err;
  fs::remove_all(dir);
}

TEST(HostileInput, FemResolutionsPastTheTetLimitAreRefused) {
  const fs::path dir = scratch("resolution");
  const std::string cube =
      "[[body]]\nname = \"j\"\ntype = \"fem\"\nshape = \"box\"\nsize = [0.04, 0.04, 0.04]\n";
  // 1e-5 m on a 4 cm box overflowed the grid's indices (a segmentation fault).
  expect_scene_refused(dir, cube + "resolution = 1e-5\n",
                       "scene.toml:6: key 'body[0].resolution' = 1e-05 m would make about "
                       "3.84e+11 tets, more than the 5000000 allowed; use a larger resolution");
  expect_scene_refused(dir, cube + "resolution = 2e-4\n",
                       "key 'body[0].resolution' = 0.0002 m would make about 4.8e+07 tets");
  // --max-tets moves the limit: 4 mm makes a 10 x 10 x 10 grid of 6,000 tets.
  const fs::path scene = dir / "scene.toml";
  std::ofstream(scene) << "[sim]\nduration = 0.01\n" << cube << "resolution = 0.004\n";
  const GripRun lowered = run_grip("simulate " + quoted(scene) + " --max-tets 5000");
  EXPECT_EQ(lowered.exit_code, 1) << lowered.err;
  EXPECT_NE(lowered.err.find("would make about 6e+03 tets, more than the 5000 allowed"),
            std::string::npos)
      << lowered.err;
  EXPECT_EQ(run_grip("simulate " + quoted(scene) + " --max-tets 6000").exit_code, 0);
  EXPECT_EQ(run_grip("simulate " + quoted(scene) + " --max-tets nan").exit_code, 2);
  // The same limit moves for a mesh prepared as an asset and a soft object in a trial.
  const fs::path cube_mesh = dir / "cube.obj";
  write_cube(cube_mesh, 0.02);
  const GripRun asset = run_grip("asset prepare " + quoted(cube_mesh) + " --out " +
                                 quoted(dir / "asset") + " --edge 0.002 --max-tets 1000");
  EXPECT_EQ(asset.exit_code, 1) << asset.err;
  EXPECT_NE(asset.err.find("more than the 1000 allowed; use a larger --edge (or raise --max-tets)"),
            std::string::npos)
      << asset.err;
  fs::remove_all(dir);
}

// A candidate file of one parallel-jaw grasp of the plate, and its hand line.
struct CandidateText {
  fs::path file;
  std::string text;
  std::size_t hand = 0;  // where "hand position" starts
};

CandidateText plate_candidates(const fs::path& dir) {
  CandidateText c{dir / "c.txt", "", 0};
  const GripRun synth = run_grip(
      "synth --object plate --gripper parallel-jaw --count 1 --seed 1 "
      "--out " +
      quoted(c.file));
  EXPECT_EQ(synth.exit_code, 0) << synth.err;
  c.text = slurp(c.file);
  c.hand = c.text.find("hand position ");
  return c;
}

// The candidate file with the `index`-th number after `field` on the hand line set to `value`.
std::string with_number(const CandidateText& c, const std::string& field, int index,
                        const std::string& value) {
  std::size_t start = c.text.find(" " + field + " ", c.hand) + field.size() + 2;
  for (int i = 0; i < index; ++i) start = c.text.find(' ', start) + 1;
  std::string text = c.text;
  text.replace(start, c.text.find(' ', start) - start, value);
  return text;
}

TEST(HostileInput, CandidateFilesWithNumbersNotFiniteOrFarAwayAreRefused) {
  const fs::path dir = scratch("candidates");
  const CandidateText c = plate_candidates(dir);
  ASSERT_NE(c.hand, std::string::npos) << c.text;
  const fs::path bad = dir / "bad.txt";
  const struct {
    std::string field;
    int index;
    std::string value;
    std::string expected;
  } cases[] = {
      // Once a division by zero inside CGAL.
      {"position", 0, "nan", "bad.txt:10: position 'nan' is not a finite number"},
      {"quaternion", 1, "nan", "bad.txt:10: quaternion 'nan' is not a finite number"},
      {"quaternion", 0, "0", "bad.txt:10: the quaternion is not a unit quaternion"},
      // Once a trial that never ended.
      {"position", 2, "1e300",
       "bad.txt:10: position lies 1e+300 m from the object's origin; a candidate must lie within "
       "10 m of it"},
  };
  for (const auto& k : cases) {
    std::ofstream(bad) << with_number(c, k.field, k.index, k.value);
    const GripRun run = run_grip("trial --candidates " + quoted(bad) + " --threads 1 --report " +
                                 quoted(dir / "r.json"));
    EXPECT_EQ(run.exit_code, 1) << k.value << run.err;
    EXPECT_EQ(count_lines(run.err), 1) << run.err;
    EXPECT_NE(run.err.find(k.expected), std::string::npos) << run.err;
    EXPECT_FALSE(fs::exists(dir / "r.json"));
  }
  fs::remove_all(dir);
}

TEST(HostileInput, CandidateCountsTheFileDoesNotHoldAreRefusedBeforeAllocating) {
  const fs::path dir = scratch("counts");
  const CandidateText c = plate_candidates(dir);
  const fs::path bad = dir / "bad.txt";
  // `what` replaced by `by` in the file: each count once reserved its memory up front and ended
  // in an out-of-memory error.
  const struct {
    std::string what, by, expected;
  } cases[] = {
      {"\ncount 1\n", "\ncount 1000000000\n",
       "bad.txt:8: candidate count 1000000000 is more than the 1000000 a candidate file may hold"},
      {"\ncount 1\n", "\ncount 1000000\n", "bad.txt:"},
      {"\nenergies ", "\nenergies 1000000000 ",
       "bad.txt:7: energy count is 1000000000 but the line holds only"},
      {" contacts ", " contacts 1000000000 ",
       "bad.txt:10: contact count is 1000000000 but the line holds only"},
  };
  for (const auto& k : cases) {
    std::string text = c.text;
    const std::size_t at = text.find(k.what);
    ASSERT_NE(at, std::string::npos) << k.what << text;
    std::string by = k.by;
    if (k.what != "\ncount 1\n") {
      // Drop the old count after the keyword.
      const std::size_t number = at + k.what.size();
      text.erase(number, text.find(' ', number) + 1 - number);
    }
    text.replace(at, k.what.size(), by);
    std::ofstream(bad) << text;
    const GripRun run = run_grip("trial --candidates " + quoted(bad) + " --threads 1 --report " +
                                 quoted(dir / "r.json"));
    EXPECT_EQ(run.exit_code, 1) << k.by << run.err;
    EXPECT_EQ(count_lines(run.err), 1) << run.err;
    EXPECT_NE(run.err.find(k.expected), std::string::npos) << run.err;
    EXPECT_FALSE(fs::exists(dir / "r.json"));
  }
  fs::remove_all(dir);
}

TEST(HostileInput, SynthOptionsOutOfTheirRangeAreUsageErrors) {
  const fs::path dir = scratch("synth");
  const std::string base =
      "synth --object plate --gripper parallel-jaw --seed 1 --out " + quoted(dir / "c.txt") + " ";
  const struct {
    std::string options, expected;
  } cases[] = {
      {"--count 0", "--count: must be a whole number from 1 to 1000000, not '0'"},
      {"--count 1000001", "--count: must be a whole number from 1 to 1000000, not '1000001'"},
      {"--count 1 --steps 0", "--steps: must be a whole number >= 1, not '0'"},
      {"--count 1 --d-hat 0", "--d-hat: must be a finite number > 0, not '0'"},
      {"--count 1 --d-hat nan", "--d-hat: must be a finite number > 0, not 'nan'"},
      {"--count 1 --margin -1e-3", "--margin: must be a finite number >= 0, not '-1e-3'"},
      {"--count 1 --margin inf", "--margin: must be a finite number >= 0, not 'inf'"},
  };
  for (const auto& k : cases) {
    const GripRun run = run_grip(base + k.options);
    EXPECT_EQ(run.exit_code, 2) << k.options << run.err;
    EXPECT_EQ(count_lines(run.err), 1) << run.err;
    EXPECT_NE(run.err.find(k.expected), std::string::npos) << run.err;
    EXPECT_FALSE(fs::exists(dir / "c.txt"));
  }
  fs::remove_all(dir);
}

// A 4 cm cube written in centimetres is a 4 m cube: no gripper takes it, and the warning names its
// size and the --scale that fixes it; with --scale 0.01 it takes candidates. A category that does
// not fit names its seed instead.
TEST(HostileInput, AMeshInCentimetresNamesItsSizeAndTheScaleThatFixesIt) {
  const fs::path dir = scratch("units");
  const fs::path mesh = dir / "cube_cm.obj";
  write_cube(mesh, 2.0);
  const std::string synth = "synth --object " + quoted(mesh) +
                            " --gripper parallel-jaw --count 1 --seed 1 --out " +
                            quoted(dir / "c.txt");
  const GripRun metres = run_grip(synth);
  EXPECT_EQ(metres.exit_code, 1) << metres.err;
  EXPECT_NE(metres.err.find("the object (4 x 4 x 4 m at --scale 1)"), std::string::npos)
      << metres.err;
  EXPECT_NE(metres.err.find("--scale 0.01"), std::string::npos) << metres.err;
  const GripRun centimetres = run_grip(synth + " --scale 0.01");
  EXPECT_EQ(centimetres.exit_code, 0) << centimetres.err;
  // A category's shape comes from the seed, not from a file's units: the 16 cm box of seed 1
  // does not fit the 85 mm jaws, and the hint is another seed, not --scale.
  const GripRun box =
      run_grip("synth --object box --gripper parallel-jaw --count 1 --seed 1 --out " +
               quoted(dir / "box.txt"));
  EXPECT_EQ(box.exit_code, 1) << box.err;
  EXPECT_NE(box.err.find("m, the box of --seed 1) may not fit the gripper; another --seed draws "
                         "another size"),
            std::string::npos)
      << box.err;
  EXPECT_EQ(box.err.find("--scale"), std::string::npos) << box.err;
  fs::remove_all(dir);
}

// `grip farm` on a small job with `extra` appended (it may reopen a table): refused in one line
// holding `expected`, exit 1, and no dataset nor its folder created.
void expect_job_refused(const fs::path& dir, const std::string& extra,
                        const std::string& expected) {
  const fs::path job = dir / "job.toml";
  const fs::path out = dir / "out";
  std::ofstream(job) << "[job]\nname = \"h\"\noutput = \"" << (out / "dataset.h5").string()
                     << "\"\n\n[[grippers]]\nname = \"parallel-jaw\"\ncandidates = 1\n"
                     << extra;
  const GripRun run = run_grip("farm " + quoted(job) + " --threads 1");
  EXPECT_EQ(run.exit_code, 1) << extra << run.err;
  EXPECT_EQ(count_lines(run.err), 1) << run.err;
  EXPECT_NE(run.err.find(expected), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(out)) << extra;
}

TEST(HostileInput, JobFilesPastTheTrialLimitsAreRefusedBeforeAnyFile) {
  const fs::path dir = scratch("job");
  const std::string rigid = "[[objects]]\ncategory = \"cylinder\"\n";
  // A tiny dt overflowed the trial's step count.
  expect_job_refused(dir, rigid + "[physics]\ndt = 1e-12\n",
                     "job.toml:11: key 'physics.dt' makes a trial of up to 3.6e+12 steps "
                     "(settle_max_steps + 6 x (phase_duration + rest_duration) / dt), more than "
                     "the 10000000 allowed; use a larger [physics] dt or a shorter [trial] "
                     "phase_duration or rest_duration");
  expect_job_refused(dir, rigid + "[trial]\nphase_duration = 1e300\n",
                     "key 'trial.phase_duration' makes a trial of up to");
  expect_job_refused(dir, rigid + "[trial]\nrest_duration = 1e300\n",
                     "key 'trial.rest_duration' makes a trial of up to");
  expect_job_refused(dir, rigid + "[trial]\nrest_duration = -1\n",
                     "key 'trial.rest_duration' must be a non-negative time (s)");
  expect_job_refused(dir, rigid + "[trial]\nobject_damping = -0.001\n",
                     "key 'trial.object_damping' must be a non-negative time (s, Rayleigh beta)");
  expect_job_refused(dir, rigid + "[physics]\ndt = 0\n", "key 'physics.dt' must be positive");
  // 1e8 frames once created a 1.18 TB dataset, then ran out of memory.
  expect_job_refused(dir, rigid + "[outputs]\nclosing_frames = 100000000\n",
                     "job.toml:11: key 'outputs.closing_frames' makes closing_frames + "
                     "validation_frames more than the 10000 frames a trial may record");
  expect_job_refused(dir, rigid + "[outputs]\nvalidation_frames = 99999996\n",
                     "key 'outputs.validation_frames' makes closing_frames + validation_frames");
  // A soft object's tet edge past the tet limit: refused before meshing.
  expect_job_refused(dir, "[[objects]]\ncategory = \"capsule\"\nsoft = true\ntet_edge = 1e-5\n",
                     "[[objects]] tet_edge: an edge of 1e-05 m would make about");
  expect_job_refused(dir, "[[objects]]\ncategory = \"capsule\"\nsoft = true\ntet_growth = -0.5\n",
                     "key 'objects[0].tet_growth' must lie in [0, 4]");
  expect_job_refused(dir, "[[objects]]\ncategory = \"mug\"\nsoft = true\ntets_across = 0.5\n",
                     "key 'objects[0].tets_across' must lie in [1, 8]");
  expect_job_refused(dir, "[[objects]]\nmesh = \"a.obj\"\ntets_across = 2\n",
                     "key 'objects[0].tets_across' applies to categories only");
  // A billion objects once planned for hours, holding every candidate in memory, and a stop
  // signal waited for planning to end.
  expect_job_refused(dir, "[[objects]]\ncategory = \"cylinder\"\ncount = 1000000000\n",
                     "job.toml:10: key 'objects[0].count' makes 1e+09 candidates (1e+09 objects x "
                     "1 candidates per object), more than the job's limit of 1000000 ([farm] "
                     "max_candidates)");
  // A job's own tet limit, below what its soft capsule needs.
  expect_job_refused(dir,
                     "[[objects]]\ncategory = \"capsule\"\nsoft = true\n[farm]\nmax_tets = 100\n",
                     "more than the 100 allowed ([farm] max_tets); use a larger tet_edge");
  // A billion D1/D2 points per surface: 24 GB a trial, a bare std::bad_alloc.
  expect_job_refused(dir, rigid + "[trial]\nmetric_samples = 1000000000\n",
                     "key 'trial.metric_samples' is 1000000000 surface points per gripper, more "
                     "than the 10000000 a trial may hold");
  fs::remove_all(dir);
}

TEST(HostileInput, TrialOptionsOutOfTheirRangeAreUsageErrors) {
  const fs::path dir = scratch("options");
  const CandidateText c = plate_candidates(dir);
  const struct {
    std::string options;
    std::string expected;
  } cases[] = {
      {"--friction nan", "grip: --friction: must be a finite number >= 0, not 'nan'"},
      {"--friction -1", "--friction: must be a finite number >= 0, not '-1'"},
      {"--density inf", "--density: must be a finite number > 0, not 'inf'"},
      {"--seed -1", "--seed: must be a whole number >= 0, not '-1'"},
      {"--grip-force nan", "--grip-force: must be a finite number > 0, not 'nan'"},
      {"--grip-force -50", "--grip-force: must be a finite number > 0, not '-50'"},
      {"--squeeze-speed -0.01", "--squeeze-speed: must be a finite number > 0, not '-0.01'"},
      {"--soft --poisson 0.5", "--poisson: must be a finite number in (-1, 0.5), not '0.5'"},
      {"--soft --youngs 0", "--youngs: must be a finite number > 0, not '0'"},
      {"--soft --tet-edge nan", "--tet-edge: must be a finite number > 0, not 'nan'"},
      {"--youngs 2e5", "--youngs: applies to soft objects only: add --soft"},
      {"--poisson 0.3", "--poisson: applies to soft objects only: add --soft"},
      {"--tet-edge 0.01", "--tet-edge: applies to soft objects only: add --soft"},
      {"--tets-across 1", "--tets-across: applies to soft objects only: add --soft"},
      {"--soft --tets-across 0.5", "--tets-across: Value 0.5 not in range"},
      {"--finger-layers 0", "--finger-layers: Value 0 not in range 1 to 32"},
      {"--finger-edge 0.05", "--finger-edge: Value 0.05 not in range 0.001000 to 0.010000"},
  };
  for (const auto& k : cases) {
    const GripRun run = run_grip("trial --candidates " + quoted(c.file) + " " + k.options +
                                 " --threads 1 --report " + quoted(dir / "r.json"));
    EXPECT_EQ(run.exit_code, 2) << k.options << run.err;
    EXPECT_EQ(count_lines(run.err), 1) << run.err;
    EXPECT_NE(run.err.find(k.expected), std::string::npos) << run.err;
    EXPECT_FALSE(fs::exists(dir / "r.json"));
  }
  // A soft object's tet edge past the tet limit: refused before meshing.
  const GripRun fine =
      run_grip("trial --candidates " + quoted(c.file) +
               " --soft --tet-edge 1e-5 --threads 1 --report " + quoted(dir / "r.json"));
  EXPECT_EQ(fine.exit_code, 1) << fine.err;
  EXPECT_NE(fine.err.find("--tet-edge: a tet edge of 1e-05 m would make about"), std::string::npos)
      << fine.err;
  EXPECT_NE(fine.err.find("more than the 5000000 allowed; use a larger --tet-edge"),
            std::string::npos)
      << fine.err;
  // The plate's candidates are the rigid jaws': they have no finger mesh to set.
  const GripRun jaws =
      run_grip("trial --candidates " + quoted(c.file) + " --finger-layers 2 --threads 1 --report " +
               quoted(dir / "r.json"));
  EXPECT_EQ(jaws.exit_code, 1) << jaws.err;
  EXPECT_NE(jaws.err.find("--finger-layers: only the fin-ray gripper has a meshed finger, not "
                          "'parallel-jaw'; leave it out"),
            std::string::npos)
      << jaws.err;
  EXPECT_FALSE(fs::exists(dir / "r.json"));
  // --max-tets moves that limit: the plate at the default edge needs more than 10.
  const GripRun few =
      run_grip("trial --candidates " + quoted(c.file) +
               " --soft --max-tets 10 --threads 1 --report " + quoted(dir / "r.json"));
  EXPECT_EQ(few.exit_code, 1) << few.err;
  EXPECT_NE(few.err.find("more than the 10 allowed; use a larger --tet-edge (or raise --max-tets)"),
            std::string::npos)
      << few.err;
  fs::remove_all(dir);
}

TEST(HostileInput, RangeErrorsSayTheRangeInWords) {
  // CLI11's own checks printed their bound as a 309-digit number.
  for (const auto& [options, expected] :
       {std::pair<std::string, std::string>{"simulate s.toml --threads -1",
                                            "grip: --threads: must be a whole number >= 0, not "
                                            "'-1'"},
        {"bench batch --scene s.toml --envs 1,0", "--envs: must be a whole number >= 1, not '0'"},
        {"bench model --repeats 0", "--repeats: must be a whole number >= 1, not '0'"},
        {"farm job.toml --batch 1.5", "--batch: must be a whole number >= 0, not '1.5'"},
        {"synth --object box --gripper fin-ray --count 1 --seed -1 --out c.txt",
         "--seed: must be a whole number >= 0, not '-1'"},
        // Past 64 bits a count was saturated, not refused.
        {"bench scale --objects 99999999999999999999",
         "--objects: must be a whole number >= 1, not '99999999999999999999'"},
        {"bench scale --seed -1", "--seed: must be a whole number >= 0, not '-1'"},
        // Options CLI11 checked, or none did: NaN passed CLI11's ranges.
        {"bench scale --soft-fraction nan", "--soft-fraction: must be a finite number from 0 to 1"},
        {"bench scale --startup nan", "--startup: must be a finite number >= 0, not 'nan'"},
        {"bench labels --newton-tol nan", "--newton-tol: must be a finite number > 0, not 'nan'"},
        {"bench labels --friction-lag 0", "--friction-lag: must be a whole number >= 1, not '0'"},
        {"bench trial --repeats -1", "--repeats: must be a whole number >= 1, not '-1'"},
        {"bench trial --candidates 0", "--candidates: must be a whole number >= 1, not '0'"},
        {"bench linear --cells 0.01,nan", "--cells: must be a finite number > 0, not 'nan'"},
        // --edge inf once reached the tetrahedralization: SIGFPE.
        {"asset prepare m.obj --out a --edge inf",
         "--edge: must be a finite number > 0, not 'inf'"},
        {"asset prepare m.obj --out a --edge 0.01 --alpha -1",
         "--alpha: must be a finite number > 0, not '-1'"},
        {"asset prepare m.obj --out a --edge 0.01 --seed -2",
         "--seed: must be a whole number >= 0, not '-2'"}}) {
    const GripRun run = run_grip(options);
    EXPECT_EQ(run.exit_code, 2) << options << run.err;
    EXPECT_EQ(count_lines(run.err), 1) << run.err;
    EXPECT_NE(run.err.find(expected), std::string::npos) << run.err;
    EXPECT_LT(run.err.size(), 200u) << run.err;
  }
}

TEST(HostileInput, PathsWithQuotesAndBackslashesRoundTripThroughTheReports) {
  const fs::path dir = scratch("q\"uote\\d");
  // grip simulate names the scene file in its report.
  const fs::path scene = dir / "sc\"ene\\1.toml";
  std::ofstream(scene) << "[sim]\nduration = 0.02\n" << kBox;
  const fs::path report = dir / "re\"port\\.json";
  const GripRun simulate = run_grip("simulate " + quoted(scene) + " --report " + quoted(report));
  ASSERT_EQ(simulate.exit_code, 0) << simulate.err;
  const nlohmann::json scenes = nlohmann::json::parse(slurp(report));
  EXPECT_EQ(scenes["scenes"][0]["scene"], scene.string());

  // grip trial names the mesh file its object came from: a 4 cm cube.
  const fs::path mesh = dir / "cu\"be\\1.obj";
  write_cube(mesh, 0.02);
  const fs::path candidates = dir / "c.txt";
  const GripRun synth =
      run_grip("synth --object " + quoted(mesh) +
               " --gripper parallel-jaw --count 1 --seed 1 --out " + quoted(candidates));
  ASSERT_EQ(synth.exit_code, 0) << synth.err;
  const GripRun trial = run_grip("trial --candidates " + quoted(candidates) +
                                 " --threads 1 --report " + quoted(report));
  ASSERT_EQ(trial.exit_code, 0) << trial.err;
  const nlohmann::json trials = nlohmann::json::parse(slurp(report));
  EXPECT_EQ(trials["object"], mesh.string());
  fs::remove_all(dir);
}

TEST(HostileInput, ABodyWhollyInsideAnotherIsAnIntersectingStart) {
  const fs::path dir = scratch("inside");
  // No surfaces cross, so the exact intersection test saw nothing: "ok", intersection-free.
  const fs::path scene = dir / "scene.toml";
  std::ofstream(scene) << "[sim]\nduration = 0.02\n\n"
                       << "[[body]]\nname = \"outer\"\ntype = \"affine\"\nshape = \"box\"\n"
                       << "size = [0.2, 0.2, 0.2]\n\n"
                       << "[[body]]\nname = \"inner\"\ntype = \"affine\"\nshape = \"sphere\"\n"
                       << "radius = 0.03\n";
  const GripRun run = run_grip("simulate " + quoted(scene));
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_EQ(count_lines(run.err), 1) << run.err;
  EXPECT_NE(run.err.find("scene.toml: simulation failed: intersecting start: body 'inner' lies "
                         "wholly inside body 'outer'; move it out"),
            std::string::npos)
      << run.err;
  const nlohmann::json report = nlohmann::json::parse(run.out);
  EXPECT_EQ(report["scenes"][0]["status"], "failed");
  EXPECT_EQ(report["scenes"][0]["intersection_free"], false);
  EXPECT_EQ(report["scenes"][0]["steps"], 0);
  fs::remove_all(dir);
}

TEST(HostileInput, OutputPathsThatCannotBeWrittenAreUsageErrors) {
  const fs::path dir = scratch("outputs");
  const fs::path folder = dir / "folder";
  const fs::path file = dir / "file";
  fs::create_directories(folder);
  std::ofstream(file) << "kept\n";
  const std::string f = quoted(folder), x = quoted(file);
  // Each was found only after planning or after the whole run, or not at all.
  const struct {
    std::string arguments, expected;
  } cases[] = {
      {"simulate s.toml --report " + f,
       "grip: --report: '" + folder.string() + "' is a directory; give a file path"},
      {"simulate s.toml --report " + quoted(file / "r.json"),
       "--report: '" + file.string() + "' is a file, not a folder; choose another path"},
      {"trial --candidates c.txt --report " + f,
       "--report: '" + folder.string() + "' is a directory"},
      {"trial --candidates c.txt --vtk " + x,
       "--vtk: '" + file.string() + "' is a file, not a folder; give a folder"},
      {"synth --object box --gripper fin-ray --count 1 --seed 1 --out " + f,
       "--out: '" + folder.string() + "' is a directory; give a file path"},
      {"farm job.toml --output " + f, "--output: '" + folder.string() + "' is a directory"},
      {"farm job.toml --report " + quoted(file / "sub" / "r.json"),
       "--report: '" + file.string() + "' is a file, so folder '" + (file / "sub").string() +
           "' cannot be created; choose another path"},
      {"bench hard --out " + x, "--out: '" + file.string() + "' is a file, not a folder"},
      {"bench scaling job.toml --out " + quoted(file / "d"),
       "--out: '" + file.string() + "' is a file, so folder"},
      {"bench model --out " + x, "--out: '" + file.string() + "' is a file, not a folder"},
      {"bench accuracy --out " + x, "--out: '" + file.string() + "' is a file, not a folder"},
      {"bench robustness --out " + x, "--out: '" + file.string() + "' is a file, not a folder"},
      {"bench labels --out " + x, "--out: '" + file.string() + "' is a file, not a folder"},
      {"bench trial --out " + x, "--out: '" + file.string() + "' is a file, not a folder"},
  };
  for (const auto& k : cases) {
    const GripRun run = run_grip(k.arguments);
    EXPECT_EQ(run.exit_code, 2) << k.arguments << run.err;
    EXPECT_EQ(count_lines(run.err), 1) << run.err;
    EXPECT_NE(run.err.find(k.expected), std::string::npos) << k.expected << '\n' << run.err;
  }
  // A job's own output, known only once the job is read: refused before planning too.
  const fs::path job = dir / "job.toml";
  std::ofstream(job) << "[job]\nname = \"h\"\noutput = \"" << folder.string()
                     << "\"\n\n[[grippers]]\nname = \"parallel-jaw\"\ncandidates = 1\n"
                     << "[[objects]]\ncategory = \"cylinder\"\n";
  const GripRun farm = run_grip("farm " + quoted(job) + " --threads 1");
  EXPECT_EQ(farm.exit_code, 1) << farm.err;
  EXPECT_EQ(count_lines(farm.err), 1) << farm.err;
  EXPECT_NE(farm.err.find("job.toml: the dataset '" + folder.string() +
                          "' is a directory; give a file path (--output or [job] output)"),
            std::string::npos)
      << farm.err;
  EXPECT_EQ(slurp(file), "kept\n");
  EXPECT_TRUE(fs::is_empty(folder));
  fs::remove_all(dir);
}

TEST(HostileInput, FoldersGivenAsInputFilesAreSaidToBeFolders) {
  const fs::path dir = scratch("folders");
  const fs::path folder = dir / "in.obj";
  fs::create_directories(folder);
  const std::string f = quoted(folder);
  // A folder opened as an empty stream: "missing key", "no candidate file magic", ...
  for (const auto& [arguments, expected] :
       {std::pair<std::string, std::string>{"simulate " + f, ": is a directory, not a file"},
        {"farm " + f + " --threads 1", ": is a directory, not a job file"},
        {"trial --candidates " + f, ": is a directory, not a candidate file"},
        {"synth --object " + f + " --gripper fin-ray --count 1 --seed 1 --out " +
             quoted(dir / "c.txt"),
         "--object '" + folder.string() + "' is a directory, not a mesh file"},
        {"inspect " + f, ": is a directory, not a dataset"}}) {
    const GripRun run = run_grip(arguments);
    EXPECT_EQ(run.exit_code, 1) << arguments << run.err;
    EXPECT_EQ(count_lines(run.err), 1) << run.err;
    EXPECT_NE(run.err.find(expected), std::string::npos) << run.err;
  }
  EXPECT_FALSE(fs::exists(dir / "c.txt"));
  fs::remove_all(dir);
}

TEST(HostileInput, ContradictoryJobValuesAreRefusedWhenTheJobIsRead) {
  const fs::path dir = scratch("contradictions");
  const std::string rigid = "[[objects]]\ncategory = \"cylinder\"\n";
  // Each once passed the job and failed in planning, without file or line.
  expect_job_refused(dir, rigid + "[trial]\nsettle_steps = 10\nsettle_max_steps = 5\n",
                     "job.toml:12: key 'trial.settle_max_steps' = 5 is fewer than settle_steps "
                     "= 10, so no trial could ever settle; make settle_max_steps at least "
                     "settle_steps");
  expect_job_refused(dir, rigid + "[trial]\nsettle_steps = 300\n",
                     "job.toml:11: key 'trial.settle_steps' = 300 is more than settle_max_steps "
                     "= 200");
  expect_job_refused(dir, rigid + "[trial]\nphase_duration = 0.001\n",
                     "job.toml:11: key 'trial.phase_duration' = 0.001 s is shorter than one step "
                     "([physics] dt = 0.01 s); make phase_duration at least dt");
  expect_job_refused(dir, rigid + "[physics]\ndt = 0.5\n",
                     "job.toml:11: key 'physics.dt' = 0.5 s is longer than a gravity phase "
                     "([trial] phase_duration = 0.1 s); make dt at most phase_duration");
  fs::remove_all(dir);
}

// `grip farm` under `mpirun -np 2` (as root too, oversubscribed on a small machine).
GripRun run_farm_on_two_ranks(const std::string& arguments) {
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
  return run_command(std::string(GRIP_MPIEXEC) + " -np 2 --oversubscribe " + GRIP_EXECUTABLE +
                     " farm " + arguments);
}

TEST(HostileInput, ABadJobUnderMpirunIsOneMessageAndEveryRankExits) {
  const fs::path dir = scratch("mpirun");
  const fs::path job = dir / "job.toml";
  const fs::path out = dir / "out";
  const std::string head = "[job]\nname = \"h\"\noutput = \"" + (out / "dataset.h5").string() +
                           "\"\n\n[[grippers]]\nname = \"parallel-jaw\"\ncandidates = 1\n";
  // The soft capsule is the second object, so rank 1 prepares it alone: its error once ended
  // in MPI_ABORT while rank 0 waited for the object, and named no file or line.
  std::ofstream(job) << head
                     << "[[objects]]\ncategory = \"cylinder\"\n[[objects]]\ncategory = "
                        "\"capsule\"\nsoft = true\ntet_edge = 1e-5\n";
  const GripRun tets = run_farm_on_two_ranks(quoted(job) + " --threads 1");
  EXPECT_NE(tets.exit_code, 0) << tets.err;
  EXPECT_EQ(count_of(tets.err, "[error]"), 1) << tets.err;
  EXPECT_NE(tets.err.find("job.toml:13: [[objects]] tet_edge: an edge of 1e-05 m would make "
                          "about"),
            std::string::npos)
      << tets.err;
  EXPECT_EQ(tets.err.find("MPI_ABORT"), std::string::npos) << tets.err;
  EXPECT_FALSE(fs::exists(out));

  // A value every rank refuses when it reads the job: one message too.
  std::ofstream(job) << head
                     << "[[objects]]\ncategory = \"cylinder\"\n[trial]\nsettle_steps = 300\n";
  const GripRun settle = run_farm_on_two_ranks(quoted(job) + " --threads 1");
  EXPECT_NE(settle.exit_code, 0) << settle.err;
  EXPECT_EQ(count_of(settle.err, "[error]"), 1) << settle.err;
  EXPECT_NE(settle.err.find("job.toml:11: key 'trial.settle_steps' = 300 is more than"),
            std::string::npos)
      << settle.err;
  EXPECT_EQ(settle.err.find("MPI_ABORT"), std::string::npos) << settle.err;
  EXPECT_FALSE(fs::exists(out));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace grip::testing
