// `grip farm` and `grip bench scaling` as a user runs them: a bad job file or an existing
// dataset is one message naming the file and the fix with exit status 1, progress lines come
// while the trials run, a trial failing on one rank of two is one message and resumable, the
// scaling benchmark writes its table for every setting, and their JSON keeps any path as it is;
// a solver failure is logged with the solver's reason;
// a bimanual job's dataset holds both grippers' poses, joints and frames, the same on 1 and 2
// ranks, and grip inspect reads it; a soft gripper from a description file runs through grip
// synth, grip trial and a job.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>

#include "tests/app/run_grip.hpp"
#include "tests/farm/farm_test_job.hpp"
#include "tests/grippers/described_gripper_files.hpp"

namespace grip::farm {
namespace {

namespace fs = std::filesystem;

class FarmCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("grip_farm_cli_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

using grip::testing::quoted;

TEST_F(FarmCli, BadJobIsOneMessageNamingFileLineAndKey) {
  testing::write_file(dir_ / "bad.toml",
                      "[job]\nname = \"bad\"\n[[objects]]\ncategory = \"cylinder\"\ncuont = 2\n"
                      "[[grippers]]\nname = \"parallel-jaw\"\n");
  const auto run = grip::testing::run_grip("farm " + (dir_ / "bad.toml").string() + " --output " +
                                           (dir_ / "bad.h5").string());
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("bad.toml:5"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("did you mean 'objects[0].count'"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(dir_ / "bad.h5"));
}

TEST_F(FarmCli, ExistingDatasetIsRefusedUntouched) {
  testing::write_file(dir_ / "job.toml", testing::small_job(1, 1, false));
  testing::write_file(dir_ / "data.h5", "someone's file");
  const auto run = grip::testing::run_grip("farm " + (dir_ / "job.toml").string() + " --output " +
                                           (dir_ / "data.h5").string());
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("data.h5: the dataset already exists"), std::string::npos) << run.err;
  EXPECT_EQ(grip::testing::slurp(dir_ / "data.h5"), "someone's file");
}

TEST_F(FarmCli, ScalingBenchmarkWritesATableRowPerSetting) {
  testing::write_file(dir_ / "job.toml", testing::small_job(1, 2, false));
  const auto run = grip::testing::run_grip("bench scaling " + (dir_ / "job.toml").string() +
                                           " --ranks 1,2 --envs 1 --repeats 1 --out " +
                                           (dir_ / "scaling").string());
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string csv = grip::testing::slurp(dir_ / "scaling" / "scaling.csv");
  EXPECT_EQ(csv.rfind("ranks,threads,envs,batch,trials,", 0), 0u) << csv;
  EXPECT_NE(csv.find("\n1,"), std::string::npos) << csv;
  EXPECT_NE(csv.find("\n2,"), std::string::npos) << csv;
  EXPECT_NE(run.out.find("\"speedup\": 1.0000"), std::string::npos) << run.out;  // the first row
}

TEST_F(FarmCli, ReportsKeepPathsWithQuotesBackslashesAndNewlines) {
  const fs::path odd = dir_ / "we\"ird\\dir\nx";
  fs::create_directories(odd);
  const fs::path job = odd / "job \"q\".toml", dataset = odd / "data \"1\".h5",
                 report = odd / "report \"1\".json";
  testing::write_file(job, testing::small_job(1, 1, false));
  const auto farm = grip::testing::run_grip("farm " + quoted(job) + " --output " + quoted(dataset) +
                                            " --report " + quoted(report));
  ASSERT_EQ(farm.exit_code, 0) << farm.err;
  const nlohmann::json read = nlohmann::json::parse(grip::testing::slurp(report), nullptr, false);
  ASSERT_FALSE(read.is_discarded()) << grip::testing::slurp(report);
  EXPECT_EQ(read["dataset"], dataset.string());
  EXPECT_EQ(read["done"], 1);

  // The scaling benchmark reads the farm's reports and ends with one JSON line naming the job.
  const auto scaling =
      grip::testing::run_grip("bench scaling " + quoted(job) +
                              " --ranks 1 --envs 1 --repeats 1 --out " + quoted(odd / "scaling"));
  ASSERT_EQ(scaling.exit_code, 0) << scaling.err;
  ASSERT_FALSE(scaling.out.empty());
  const std::string last = scaling.out.substr(scaling.out.rfind('\n', scaling.out.size() - 2) + 1);
  const nlohmann::json summary = nlohmann::json::parse(last, nullptr, false);
  ASSERT_FALSE(summary.is_discarded()) << last;
  EXPECT_EQ(summary["job"], job.string());
  EXPECT_EQ(summary["rows"][0]["trials"], 1);
}

// Progress comes while the trials run: a line with fewer trials than the total comes before the
// line of the last commit. Reporting progress at every solver step or never gives the same
// dataset.
TEST_F(FarmCli, ProgressLinesComeWhileTrialsRunAndChangeNothing) {
  testing::write_file(dir_ / "job.toml", testing::small_job(2, 2, false));
  const auto farm = [&](const std::string& interval, const std::string& name) {
    ::setenv("GRIP_PROGRESS_INTERVAL", interval.c_str(), 1);
    auto run = grip::testing::run_grip("farm " + (dir_ / "job.toml").string() + " --output " +
                                       (dir_ / name).string() + " --threads 1 --batch 1");
    ::unsetenv("GRIP_PROGRESS_INTERVAL");
    return run;
  };
  const auto live = farm("0", "live.h5");
  const auto quiet = farm("1000000", "quiet.h5");
  ASSERT_EQ(live.exit_code, 0) << live.err;
  ASSERT_EQ(quiet.exit_code, 0) << quiet.err;

  const std::size_t trials = io::DatasetReader(dir_ / "live.h5").candidates().size();
  ASSERT_GE(trials, 2u);
  const std::string total = "/" + std::to_string(trials) + " trials";
  const std::size_t first = live.err.find("1" + total);
  const std::size_t committed = live.err.find(std::to_string(trials) + total + " (100.0%)");
  EXPECT_NE(first, std::string::npos) << live.err;
  EXPECT_NE(committed, std::string::npos) << live.err;
  EXPECT_LT(first, committed) << live.err;
  EXPECT_NE(live.err.find("planning: 1/2 objects prepared"), std::string::npos) << live.err;
  EXPECT_EQ(live.err.find('\r'), std::string::npos) << "not a terminal: log lines only";
  // Without live progress only the commit and the end of planning are logged.
  EXPECT_EQ(quiet.err.find("1" + total), std::string::npos) << quiet.err;
  EXPECT_NE(quiet.err.find(std::to_string(trials) + total + " (100.0%)"), std::string::npos);
  EXPECT_NE(quiet.err.find("planning: 2/2 objects prepared"), std::string::npos) << quiet.err;
  testing::expect_same_dataset(dir_ / "quiet.h5", dir_ / "live.h5");
}

TEST_F(FarmCli, BadProgressIntervalIsAUsageError) {
  ::setenv("GRIP_PROGRESS_INTERVAL", "soon", 1);
  const auto run = grip::testing::run_grip("farm " + (dir_ / "job.toml").string());
  ::unsetenv("GRIP_PROGRESS_INTERVAL");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("GRIP_PROGRESS_INTERVAL: must be a number of seconds >= 0, not 'soon'"),
            std::string::npos)
      << run.err;
}

// A candidate the solver gives up on (one Newton iteration allowed, no retries) is recorded as
// newton_limit, and the log says which candidate and, in the solver's words, why.
TEST_F(FarmCli, SolverFailuresAreLoggedWithTheSolversReason) {
  testing::write_file(dir_ / "job.toml", testing::small_job(1, 1, false) +
                                             "\n[physics]\nmax_newton_iters = 1\n"
                                             "max_step_halvings = 0\n");
  const auto run = grip::testing::run_grip("farm " + quoted(dir_ / "job.toml") + " --output " +
                                           quoted(dir_ / "data.h5") + " --threads 1");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const io::DatasetReader reader(dir_ / "data.h5");
  ASSERT_EQ(reader.candidates().size(), 1u);
  EXPECT_EQ(reader.candidates()[0].failure, io::FailureKind::kNewtonLimit);
  EXPECT_NE(run.err.find("[warning] candidate 0 (cylinder-0 with parallel-jaw): newton_limit: "),
            std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find("Newton"), std::string::npos) << run.err;
}

// A trial that throws on rank 1 alone (CHOLMOD fails there: a preload library on that rank
// only): rank 0 says so once, every rank exits 1 without MPI_Abort or a hang, the rounds
// committed before are kept, and --resume completes the same dataset as a clean run.
TEST_F(FarmCli, ATrialFailingOnOneRankIsOneMessageAndResumable) {
  testing::write_file(dir_ / "job.toml", testing::small_job(1, 4, false));
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
  const std::string farm = std::string(GRIP_EXECUTABLE) + " farm " + quoted(dir_ / "job.toml") +
                           " --output " + quoted(dir_ / "data.h5") + " --threads 1 --batch 1";
  const std::string err = (dir_ / "mpirun.err").string();
  const std::string command = std::string(GRIP_MPIEXEC) + " --oversubscribe -np 1 " + farm +
                              " : -np 1 -x LD_PRELOAD=" + GRIP_FAIL_CHOLMOD + " " + farm +
                              " >/dev/null 2>" + err;
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 1);
  const std::string text = grip::testing::slurp(err);
  const std::size_t at = text.find("[error] rank 1: the trials of candidates ");
  EXPECT_NE(at, std::string::npos) << text;
  EXPECT_EQ(text.find("[error]", at + 1), std::string::npos) << "one message: " << text;
  EXPECT_NE(text.find(" (cylinder-0 with parallel-jaw) failed: CHOLMOD analysis failed; the "
                      "results committed so far are kept (grip farm --resume continues)"),
            std::string::npos)
      << text;
  EXPECT_EQ(text.find("MPI_ABORT"), std::string::npos) << text;
  {
    const io::DatasetReader reader(dir_ / "data.h5");
    const std::vector<std::uint8_t> done = reader.done();
    const auto committed = std::count(done.begin(), done.end(), 1);
    EXPECT_GE(committed, 1) << "rank 0's work unit of the failed round is committed";
    EXPECT_LT(committed, 4);
  }

  const auto resume =
      grip::testing::run_grip("farm " + quoted(dir_ / "job.toml") + " --output " +
                              quoted(dir_ / "data.h5") + " --threads 1 --batch 1 --resume");
  ASSERT_EQ(resume.exit_code, 0) << resume.err;
  const auto clean = grip::testing::run_grip("farm " + quoted(dir_ / "job.toml") + " --output " +
                                             quoted(dir_ / "clean.h5") + " --threads 1");
  ASSERT_EQ(clean.exit_code, 0) << clean.err;
  testing::expect_same_dataset(dir_ / "clean.h5", dir_ / "data.h5");
}

// Two parallel-jaw grippers per trial: every record has two hands' poses and openings and four
// closing forces, the gripper record says two hands, the frames hold both grippers; 2 ranks give
// the dataset of 1, and grip inspect reads it.
TEST_F(FarmCli, BimanualJobRecordsBothGrippersAlikeOnOneAndTwoRanks) {
  testing::write_file(dir_ / "job.toml", testing::bimanual_job(2));
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
  for (const int ranks : {1, 2}) {
    const std::string command =
        std::string(GRIP_MPIEXEC) + " --oversubscribe -np " + std::to_string(ranks) + " " +
        GRIP_EXECUTABLE + " farm " + quoted(dir_ / "job.toml") + " --output " +
        quoted(dir_ / ("ranks" + std::to_string(ranks) + ".h5")) +
        " --threads 1 --batch 1 >/dev/null 2>" + quoted(dir_ / "mpirun.err");
    const int status = std::system(command.c_str());
    ASSERT_TRUE(WIFEXITED(status));
    ASSERT_EQ(WEXITSTATUS(status), 0) << grip::testing::slurp(dir_ / "mpirun.err");
  }
  testing::expect_same_dataset(dir_ / "ranks1.h5", dir_ / "ranks2.h5");

  const io::DatasetReader reader(dir_ / "ranks2.h5");
  const io::GripperRecord gripper = reader.gripper(0);
  EXPECT_EQ(gripper.hands, 2u);
  EXPECT_EQ(gripper.name, "parallel-jaw-bimanual");
  EXPECT_EQ(gripper.joint_names, std::vector<std::string>{"opening"});
  EXPECT_EQ(gripper.finger_names.size(), 2u);
  const std::vector<io::CandidateRecord> records = reader.candidates();
  ASSERT_EQ(records.size(), 2u);
  for (std::size_t i = 0; i < records.size(); ++i) {
    const io::CandidateRecord& r = records[i];
    EXPECT_EQ(r.status, io::Status::kSuccess) << i;
    ASSERT_EQ(r.hand_poses.size(), 24u);
    EXPECT_EQ(r.joints.size(), 2u);
    EXPECT_EQ(r.closing_forces.size(), 4u);
    // Two grippers at two places: the translations (entries 3, 7, 11 of each pose) differ.
    const double apart =
        std::hypot(r.hand_poses[3] - r.hand_poses[15], r.hand_poses[7] - r.hand_poses[19],
                   r.hand_poses[11] - r.hand_poses[23]);
    EXPECT_GT(apart, 0.02) << i;
    const std::optional<io::TrajectoryRecord> t = reader.trajectory(i);
    ASSERT_TRUE(t.has_value());
    const std::size_t frames = 10;
    EXPECT_EQ(t->hand_poses.size(), frames * 2 * 12);
    EXPECT_EQ(t->joints.size(), frames * 2);
    // The record holds both grippers' surfaces, as each frame does.
    EXPECT_EQ(t->gripper_vertices.size(), frames * gripper.vertex_count() * 3);
  }

  const auto inspect = grip::testing::run_grip("inspect " + quoted(dir_ / "ranks2.h5"));
  EXPECT_EQ(inspect.exit_code, 0) << inspect.err;
  EXPECT_NE(inspect.out.find("parallel-jaw-bimanual"), std::string::npos) << inspect.out;
  EXPECT_NE(inspect.out.find("2 (2 done, 0 pending)"), std::string::npos) << inspect.out;
}

// A user's soft gripper (a box finger meshed in millimetres, its description beside it) in grip
// synth, grip trial and a job's [[grippers]] description, recorded as the built-in ones are.
TEST_F(FarmCli, ADescribedSoftGripperRunsThroughSynthTrialAndAJob) {
  fs::create_directories(dir_ / "finger");
  const fs::path description = grip::testing::write_described_gripper(dir_ / "finger");
  const auto synth =
      grip::testing::run_grip("synth --object cylinder --seed 3 --scale 0.5 --gripper " +
                              quoted(description) + " --count 1 --out " + quoted(dir_ / "c.txt"));
  ASSERT_EQ(synth.exit_code, 0) << synth.err;
  EXPECT_NE(grip::testing::slurp(dir_ / "c.txt").find("\ngripper test-soft-jaws described\n"),
            std::string::npos);
  const auto bare = grip::testing::run_grip("trial --candidates " + quoted(dir_ / "c.txt"));
  EXPECT_EQ(bare.exit_code, 1);
  EXPECT_NE(bare.err.find("pass --gripper with its description file"), std::string::npos)
      << bare.err;
  const auto trial = grip::testing::run_grip("trial --candidates " + quoted(dir_ / "c.txt") +
                                             " --gripper " + quoted(description) +
                                             " --threads 1 --report " + quoted(dir_ / "r.json"));
  ASSERT_EQ(trial.exit_code, 0) << trial.err;
  const nlohmann::json report = nlohmann::json::parse(std::ifstream(dir_ / "r.json"));
  ASSERT_EQ(report["trials"].size(), 1u);
  // The box finger is symmetric across its width: its mirror image as the second finger
  // (numbered otherwise) grasps as the turned one does.
  std::string text = grip::testing::slurp(description);
  text.insert(text.find("\n[finger]"), "second_finger = \"mirrored\"\n");
  text.replace(text.find("mesh = \""), 8, "mesh = \"finger/");
  testing::write_file(dir_ / "mirrored.toml", text);
  const auto mirrored = grip::testing::run_grip("trial --candidates " + quoted(dir_ / "c.txt") +
                                                " --gripper " + quoted(dir_ / "mirrored.toml") +
                                                " --threads 1 --report " + quoted(dir_ / "m.json"));
  ASSERT_EQ(mirrored.exit_code, 0) << mirrored.err;
  const nlohmann::json& a = report["trials"][0];
  const nlohmann::json mirrored_report = nlohmann::json::parse(std::ifstream(dir_ / "m.json"));
  const nlohmann::json& b = mirrored_report["trials"][0];
  EXPECT_EQ(a["status"], b["status"]);
  ASSERT_EQ(a["closing_forces"].size(), 2u);
  for (int f = 0; f < 2; ++f) {
    const double force = a["closing_forces"][f];
    EXPECT_GT(force, 1.0);
    EXPECT_NEAR(b["closing_forces"][f].get<double>(), force, 1e-3 * force);
  }

  std::string job = testing::small_job(1, 2, false);
  const std::string jaws = "name = \"parallel-jaw\"";
  job.replace(job.find(jaws), jaws.size(), "description = \"finger/gripper.toml\"");
  testing::write_file(dir_ / "job.toml", job);
  const auto farm = grip::testing::run_grip("farm " + quoted(dir_ / "job.toml") + " --output " +
                                            quoted(dir_ / "data.h5") + " --threads 1");
  ASSERT_EQ(farm.exit_code, 0) << farm.err;
  const io::DatasetReader reader(dir_ / "data.h5");
  const io::GripperRecord gripper = reader.gripper(0);
  EXPECT_EQ(gripper.name, "test-soft-jaws");
  EXPECT_TRUE(gripper.soft);
  EXPECT_EQ(gripper.vertex_count(), 2u * 138u);    // both box fingers' surfaces
  EXPECT_EQ(gripper.tets.size(), 2u * 480u * 4u);  // ... and their tets
  const std::vector<io::CandidateRecord> records = reader.candidates();
  ASSERT_EQ(records.size(), 2u);
  for (const io::CandidateRecord& r : records) {
    // The job keeps stress by default: the squeezed fingers' is in the dataset.
    const std::optional<std::vector<float>> finger_stress = reader.finger_stress(r.id);
    ASSERT_TRUE(finger_stress.has_value());
    ASSERT_EQ(finger_stress->size(), 2u * 480u);
    EXPECT_GT(*std::max_element(finger_stress->begin(), finger_stress->end()), 0.0f);
    EXPECT_NE(r.status, io::Status::kPending);
    EXPECT_NE(r.failure, io::FailureKind::kInitialPenetration);
    EXPECT_NE(r.failure, io::FailureKind::kNewtonLimit);
    EXPECT_NE(r.failure, io::FailureKind::kNumerical);
    ASSERT_EQ(r.closing_forces.size(), 2u);
    EXPECT_GT(r.closing_forces[0], 0.0);  // the soft fingers squeezed the cylinder
  }

  // A description that is not there: one message naming the job file and the key.
  job.replace(job.find("finger/gripper.toml"), 19, "finger/missing.toml");
  testing::write_file(dir_ / "missing.toml", job);
  const auto missing = grip::testing::run_grip("farm " + quoted(dir_ / "missing.toml") +
                                               " --output " + quoted(dir_ / "missing.h5"));
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.err.find("key 'grippers[0].description' names"), std::string::npos)
      << missing.err;
  EXPECT_NE(missing.err.find("which does not exist"), std::string::npos) << missing.err;
}

}  // namespace
}  // namespace grip::farm
