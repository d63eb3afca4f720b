// The `grip` command line as a user meets it: versions, unknown commands, global options.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/app/run_grip.hpp"

namespace grip::testing {
namespace {

TEST(GripCli, VersionNamesEveryLibraryAndTheRevision) {
  const GripRun run = run_grip("--version");
  EXPECT_EQ(run.exit_code, 0) << run.err;
  for (const char* word :
       {"grip 0.", "revision", "MPI", "HDF5", "(parallel)", "PETSc", "CGAL", "Eigen"}) {
    EXPECT_NE(run.out.find(word), std::string::npos) << "missing '" << word << "' in\n" << run.out;
  }
  EXPECT_EQ(run.out.find("revision unknown"), std::string::npos) << run.out;
}

TEST(GripCli, UnknownCommandExitsTwoWithOneLine) {
  const GripRun run = run_grip("no-such-command");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(count_lines(run.err), 1) << run.err;
  EXPECT_NE(run.err.find("'no-such-command' is not a grip command"), std::string::npos) << run.err;
  EXPECT_TRUE(run.out.empty()) << run.out;
}

TEST(GripCli, UnknownOptionExitsTwoWithOneLine) {
  const GripRun run = run_grip("--no-such-option");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(count_lines(run.err), 1) << run.err;
}

TEST(GripCli, NoCommandPrintsUsageAndExitsTwo) {
  const GripRun run = run_grip("");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("Usage"), std::string::npos) << run.err;
}

TEST(GripCli, HelpExitsZero) {
  const GripRun run = run_grip("--help");
  EXPECT_EQ(run.exit_code, 0);
  EXPECT_NE(run.out.find("--log-level"), std::string::npos) << run.out;
}

TEST(GripCli, BadLogLevelIsAUsageError) {
  const GripRun bad = run_grip("--log-level loud");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("unknown log level 'loud'"), std::string::npos) << bad.err;
}

TEST(GripCli, SimulateWritesAReportAndFailsClearlyOnBadScenes) {
  const auto dir = std::filesystem::temp_directory_path();
  const auto scene = dir / ("grip_cli_scene_" + std::to_string(::getpid()) + ".toml");
  std::ofstream(scene) << "[sim]\nduration = 0.05\n[[body]]\nname = \"b\"\ntype = \"affine\"\n"
                          "shape = \"box\"\nsize = [0.1, 0.1, 0.1]\n";
  const GripRun ok = run_grip("simulate " + scene.string());
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_NE(ok.out.find("\"status\": \"ok\""), std::string::npos) << ok.out;
  EXPECT_NE(ok.out.find("\"steps\": 5"), std::string::npos) << ok.out;
  // Several scenes: one report entry each, in order.
  const GripRun two =
      run_grip("simulate " + scene.string() + " " + scene.string() + " --threads 2");
  EXPECT_EQ(two.exit_code, 0) << two.err;
  EXPECT_NE(two.out.find("\"threads\": 2"), std::string::npos) << two.out;
  const std::size_t first = two.out.find("\"steps\": 5");
  ASSERT_NE(first, std::string::npos) << two.out;
  EXPECT_NE(two.out.find("\"steps\": 5", first + 1), std::string::npos) << two.out;

  // The batch benchmark on two jittered copies: the batch ends bit-identical to the copies run
  // one after another.
  const GripRun bench =
      run_grip("bench batch --scene " + scene.string() + " --envs 1,2 --threads 2 --jitter 7");
  EXPECT_EQ(bench.exit_code, 0) << bench.err;
  EXPECT_NE(bench.out.find("{\"benchmark\": \"batch\""), std::string::npos) << bench.out;
  EXPECT_NE(bench.out.find("\"identical\": true"), std::string::npos) << bench.out;
  EXPECT_EQ(bench.out.find("\"identical\": false"), std::string::npos) << bench.out;
  EXPECT_NE(bench.out.find("\"envs\": 2, \"steps\": 5"), std::string::npos) << bench.out;
  // The same on the data-parallel engine: its batch against its own one-by-one runs.
  const GripRun host = run_grip("bench batch --scene " + scene.string() +
                                " --envs 2 --threads 2 --jitter 7 --device host");
  EXPECT_EQ(host.exit_code, 0) << host.err;
  EXPECT_NE(host.out.find("\"device\": \"host\""), std::string::npos) << host.out;
  EXPECT_NE(host.out.find("\"identical\": true"), std::string::npos) << host.out;
  // No CUDA engine to step on: exit 2 in one line naming the flag and what to use.
  const GripRun cuda = run_grip("bench batch --scene " + scene.string() + " --device cuda");
  EXPECT_EQ(cuda.exit_code, 2);
  EXPECT_EQ(count_lines(cuda.err), 1) << cuda.err;
  EXPECT_NE(cuda.err.find("--device cuda: this grip has no CUDA engine"), std::string::npos)
      << cuda.err;
  EXPECT_NE(cuda.err.find("use --device host"), std::string::npos) << cuda.err;

  std::ofstream(scene) << "[sim]\nduration = 0.05\nfoo = 1\n";
  const GripRun bad = run_grip("simulate " + scene.string());
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_EQ(count_lines(bad.err), 1) << bad.err;
  EXPECT_NE(bad.err.find(".toml:3: unknown key 'sim.foo'"), std::string::npos) << bad.err;
  std::filesystem::remove(scene);
}

// GRIP_CHECK_ARGS=1 (docs/command-line.md): the command line is parsed and validated, nothing
// runs, so a job file that does not exist is not read; a refused command line still exits 2.
TEST(GripCli, CheckArgsStopsAfterParsingAndValidation) {
  const std::string missing_job = "/nonexistent/grip_check_args_job.toml";
  const GripRun checked = run_grip_checking_args("farm " + missing_job + " --threads 1");
  EXPECT_EQ(checked.exit_code, 0) << checked.err;
  EXPECT_TRUE(checked.out.empty()) << checked.out;
  EXPECT_TRUE(checked.err.empty()) << checked.err;
  EXPECT_EQ(run_grip("farm " + missing_job).exit_code, 1);

  EXPECT_EQ(run_grip_checking_args("farm " + missing_job + " --threads -1").exit_code, 2);
  // The farm takes PETSc options for its job's PETSc groups; grip inspect takes none.
  EXPECT_EQ(run_grip_checking_args("farm " + missing_job + " -- -ksp_type cg").exit_code, 0);
  const GripRun petsc = run_grip_checking_args("inspect " + missing_job + " -- -ksp_type cg");
  EXPECT_EQ(petsc.exit_code, 2);
  EXPECT_NE(petsc.err.find("'inspect' uses no PETSc"), std::string::npos) << petsc.err;
  EXPECT_EQ(run_grip_checking_args("bench linear --repeats 1 -- -ksp_type cg").exit_code, 0);
}

// grip bench labels --refine none runs no reference, so it cannot be combined with a refinement:
// one clear refusal before anything runs.
TEST(GripCli, BenchLabelsRefusesNoneWithARefinement) {
  const GripRun run = run_grip("bench labels --refine none,dt --out /nonexistent/labels");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("--refine none runs no reference; give it alone"), std::string::npos)
      << run.err;
}

// grip trial --finger-layers and --finger-edge mesh the fin-ray finger as asked, and the report
// says how it was meshed: a coarse finger (1 layer, 6 mm edges) on a box.
TEST(GripCli, TrialMeshesTheFinRayFingerAsAskedAndRecordsIt) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("grip_cli_finger_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string candidates = (dir / "c.txt").string();
  const std::string report = (dir / "r.json").string();
  ASSERT_EQ(run_grip("synth --object box --seed 4 --gripper fin-ray --count 1 --out " + candidates)
                .exit_code,
            0);
  const GripRun run =
      run_grip("trial --candidates " + candidates +
               " --finger-layers 1 --finger-edge 0.006 --threads 1 --report " + report);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("fin-ray finger: 1 tet layers, profile edges up to 0.006 m: "),
            std::string::npos)
      << run.err;
  const nlohmann::json json = nlohmann::json::parse(std::ifstream(report));
  EXPECT_EQ(json["finger_mesh"]["layers"], 1);
  EXPECT_EQ(json["finger_mesh"]["edge_length"], 0.006);
  EXPECT_EQ(json["trials"].size(), 1u);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace grip::testing
