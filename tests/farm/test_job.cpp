// Job files: what a valid job resolves to, and a one-line error naming the file, line and key
// for each kind of mistake.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "farm/farm_object.hpp"
#include "farm/job.hpp"
#include "src/config/config.hpp"

namespace grip::farm {
namespace {

const char* const kValid = R"([job]
name = "t"
seed = 5

[[objects]]
category = "cylinder"
count = 3

[[objects]]
category = "capsule"
soft = true
tet_edge = 0.01
randomize = false
friction = 0.8

[[grippers]]
name = "parallel-jaw"
candidates = 4

[physics]
dt = 0.005

[trial]
grip_force = 40
hand_drive_stiffness = 1e5

[outputs]
validation_frames = 12
)";

// The message parse_job throws for `text`, or "" when it parses.
std::string error_of(const std::string& text, const std::filesystem::path& file = "job.toml") {
  try {
    parse_job(text, file);
  } catch (const config::ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(Job, ResolvesDefaultsAndOverrides) {
  const Job job = parse_job(kValid, "job.toml");
  EXPECT_EQ(job.name, "t");
  EXPECT_EQ(job.seed, 5u);
  EXPECT_EQ(job.output, "out/t/dataset.h5");
  ASSERT_EQ(job.objects.size(), 2u);
  EXPECT_EQ(job.objects[0].count, 3);
  EXPECT_TRUE(job.objects[1].soft);
  EXPECT_DOUBLE_EQ(job.objects[1].material.friction, 0.8);
  ASSERT_EQ(job.grippers.size(), 1u);
  EXPECT_EQ(job.grippers[0].type.kind, grippers::GripperKind::kParallelJaw);
  EXPECT_EQ(job.grippers[0].candidates, 4);
  EXPECT_DOUBLE_EQ(job.trial.sim.dt, 0.005);
  EXPECT_DOUBLE_EQ(job.trial.grip_force, 40.0);
  EXPECT_DOUBLE_EQ(job.trial.hand_drive_stiffness, 1e5);
  EXPECT_DOUBLE_EQ(job.trial.finger_stiffness, 2e4);  // the default
  EXPECT_EQ(job.trial.validation_frames, 12);
  EXPECT_EQ(job.trial.closing_frames, 40);  // the default, as GRIP's released files
  EXPECT_EQ(job.text, kValid);              // verbatim, for the dataset's provenance
  EXPECT_FALSE(job.full_trials);            // a decided trial stops by default
  EXPECT_TRUE(parse_job(std::string(kValid) + "full_trials = true\n", "job.toml").full_trials);
  EXPECT_NE(error_of(std::string(kValid) + "full_trials = 1\n").find("full_trials"),
            std::string::npos);

  bool found = false;
  for (const io::Parameter& p : resolved_parameters(job)) {
    if (p.key == "physics.dt") {
      found = true;
      EXPECT_EQ(p.value, "0.005");
    }
  }
  EXPECT_TRUE(found);
}

TEST(Job, ObjectsAreNamedAndSeededByPosition) {
  const Job job = parse_job(kValid, "job.toml");
  const std::vector<FarmObject> a = list_objects(job);
  ASSERT_EQ(a.size(), 4u);
  EXPECT_EQ(a[0].name, "cylinder-0");
  EXPECT_EQ(a[2].name, "cylinder-2");
  EXPECT_EQ(a[3].name, "capsule-0");
  EXPECT_NE(a[0].shape_seed, a[1].shape_seed);
  EXPECT_NE(a[0].material.scale, a[1].material.scale);  // randomized per object
  EXPECT_DOUBLE_EQ(a[3].material.scale, 1.0);           // randomize = false
  EXPECT_DOUBLE_EQ(a[3].material.friction, 0.8);
  const std::vector<FarmObject> b = list_objects(job);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].shape_seed, b[i].shape_seed);
    EXPECT_EQ(a[i].material.friction, b[i].material.friction);
  }
  // Another seed, other shapes.
  std::string reseeded = kValid;
  reseeded.replace(reseeded.find("seed = 5"), 8, "seed = 6");
  EXPECT_NE(list_objects(parse_job(reseeded, "job.toml"))[0].shape_seed, a[0].shape_seed);
}

TEST(Job, MeshGlobsResolveFromTheJobFolder) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("grip_job_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir / "meshes");
  for (const char* name : {"b.obj", "a.obj", "c.stl"}) std::ofstream(dir / "meshes" / name) << "\n";
  const std::string text =
      "[job]\nname = \"m\"\n[[objects]]\nmesh = \"meshes/*.obj\"\nscale = 0.001\n"
      "[[grippers]]\nname = \"fin-ray\"\n";
  const Job job = parse_job(text, dir / "job.toml");
  ASSERT_EQ(job.objects.size(), 1u);
  ASSERT_EQ(job.objects[0].meshes.size(), 2u);
  EXPECT_EQ(job.objects[0].meshes[0].filename(), "a.obj");
  EXPECT_EQ(job.objects[0].meshes[1].filename(), "b.obj");
  EXPECT_EQ(list_objects(job)[1].name, "b");
  EXPECT_NE(error_of("[job]\nname = \"m\"\n[[objects]]\nmesh = \"meshes/*.ply\"\n"
                     "[[grippers]]\nname = \"fin-ray\"\n",
                     dir / "job.toml")
                .find("matches no file"),
            std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST(Job, MistakesNameTheFileLineAndKey) {
  struct Case {
    std::string from, to, expected;
  };
  const std::vector<Case> cases = {
      {"count = 3", "cuont = 3", "job.toml:7: "},                          // misspelt key
      {"count = 3", "count = 0", "objects[0].count"},                      // out of range
      {"category = \"cylinder\"", "category = \"cylindre\"", "cylindre"},  // unknown category
      {"name = \"parallel-jaw\"", "name = \"robotiq\"", "fin-ray"},        // lists the choices
      {"candidates = 4", "candidates = 4\nbimanual = true", ""},           // two grippers per trial
      {"candidates = 4", "candidates = 4\nbimanual = 1", "grippers[0].bimanual"},
      {"candidates = 4", "candidates = 4\n[[grippers]]\nname = \"parallel-jaw\"",
       "repeats the unimanual 'parallel-jaw' setting of the entry at job.toml:"},
      {"candidates = 4",
       "candidates = 4\nbimanual = true\n[[grippers]]\nname = \"parallel-jaw\"\n"
       "bimanual = true",
       "repeats the bimanual 'parallel-jaw' setting"},
      {"candidates = 4", "candidates = 4\n[[grippers]]\nname = \"parallel-jaw\"\nbimanual = true",
       ""},  // the one- and the two-gripper setting of a kind are two settings
      {"validation_frames = 12", "validation_frames = 10", "multiple of 6"},
      {"dt = 0.005", "dt = -1", "physics.dt"},
      {"hand_drive_stiffness = 1e5", "hand_drive_stiffness = 0", "hand_drive_stiffness"},
      {"friction = 0.8", "friction = 0.8\ndensity = 900", ""},  // allowed with randomize = false
      {"randomize = false", "randomize = true", "randomize = false"},  // friction is drawn
  };
  for (const Case& c : cases) {
    std::string text = kValid;
    text.replace(text.find(c.from), c.from.size(), c.to);
    const std::string message = error_of(text);
    if (c.expected.empty()) {
      EXPECT_EQ(message, "") << c.to;
    } else {
      EXPECT_NE(message.find(c.expected), std::string::npos) << c.to << " -> " << message;
      EXPECT_EQ(message.rfind("job.toml:", 0), 0u) << message;
    }
  }
  EXPECT_NE(error_of("[job]\nname = \"x\"\n[[grippers]]\nname = \"fin-ray\"\n").find("[[objects]]"),
            std::string::npos);
  EXPECT_NE(error_of("[job]\nname = \"x\"\n[[objects]]\ncategory = \"box\"\nmesh = \"a.obj\"\n"
                     "[[grippers]]\nname = \"fin-ray\"\n")
                .find("exactly one"),
            std::string::npos);
}

// `text` with its first `from` replaced by `to`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  text.replace(text.find(from), from.size(), to);
  return text;
}

// A job's size is refused before planning on the key that made it large, with what it would
// need; [farm] max_candidates raises the limit for whoever means it.
TEST(Job, TooManyCandidatesAreRefusedWithWhatTheyWouldNeed) {
  // 4 objects (3 cylinders, 1 capsule) x 4 candidates.
  EXPECT_EQ(parse_job(kValid, "job.toml").candidate_count(), 16u);

  const std::string huge = error_of(replaced(kValid, "candidates = 4", "candidates = 1000000000"));
  EXPECT_EQ(huge.rfind("job.toml:18: ", 0), 0u) << huge;  // the candidates line
  for (const char* part : {"grippers[0].candidates", "makes 4e+09 candidates",
                           "4 objects x 1e+09 candidates per object", "limit of 1000000",
                           "CPU hours", "raise [farm] max_candidates"}) {
    EXPECT_NE(huge.find(part), std::string::npos) << part << " in: " << huge;
  }
  // 1e9 objects of one candidate each: the objects' count made it.
  const std::string objects = error_of(replaced(replaced(kValid, "count = 3", "count = 1000000000"),
                                                "candidates = 4", "candidates = 1"));
  EXPECT_NE(objects.find("objects[0].count"), std::string::npos) << objects;

  // Raised, the same job reads; a limit set too low is named itself.
  const std::string big = replaced(kValid, "candidates = 4", "candidates = 500000") +
                          "[farm]\nmax_candidates = 2000000\n";
  EXPECT_EQ(error_of(big), "");
  EXPECT_EQ(parse_job(big, "job.toml").candidate_count(), 2'000'000u);
  const std::string low = kValid + std::string("[farm]\nmax_candidates = 10\n");
  EXPECT_NE(error_of(low).find("farm.max_candidates"), std::string::npos) << error_of(low);
  EXPECT_NE(error_of(kValid + std::string("[farm]\nmax_candidates = 0\n")).find("from 1 to"),
            std::string::npos);
  EXPECT_NE(error_of(kValid + std::string("[farm]\nmax_candidates = 5000000000\n"))
                .find("from 1 to 4294967295"),
            std::string::npos);
}

TEST(Job, MetricSamplesAreBoundedByWhatATrialMayHold) {
  const std::string message =
      error_of(replaced(kValid, "grip_force = 40", "grip_force = 40\nmetric_samples = 1000000000"));
  EXPECT_NE(message.find("trial.metric_samples"), std::string::npos) << message;
  EXPECT_NE(message.find("more than the 10000000"), std::string::npos) << message;
  EXPECT_EQ(
      error_of(replaced(kValid, "grip_force = 40", "grip_force = 40\nmetric_samples = 10000000")),
      "");
}

// [farm]'s PETSc groups: none by default; the keys read and bounded; groups and a size rule
// without a group's ranks are refused on their key.
TEST(Job, PetscGroupsAreReadAndCheckedOnTheirKeys) {
  const Job plain = parse_job(kValid, "job.toml");
  EXPECT_EQ(plain.petsc.group_ranks, 0);
  EXPECT_EQ(plain.petsc.ranks(), 0);
  EXPECT_EQ(plain.petsc.min_dofs, 0);  // no rule on DOFs
  EXPECT_EQ(plain.petsc.min_factor_mib, PetscGroupSetting::kDefaultMinFactorMib);

  const std::string farm = std::string(kValid) + "\n[farm]\npetsc_group_ranks = 2\n";
  const Job grouped = parse_job(
      farm + "petsc_groups = 3\npetsc_min_dofs = 5000\npetsc_min_factor_mib = 512.5\n", "job.toml");
  EXPECT_EQ(grouped.petsc.group_ranks, 2);
  EXPECT_EQ(grouped.petsc.groups, 3);
  EXPECT_EQ(grouped.petsc.ranks(), 6);
  EXPECT_EQ(grouped.petsc.min_dofs, 5000);
  EXPECT_EQ(grouped.petsc.min_factor_mib, 512.5);
  EXPECT_EQ(grouped.petsc.location.rfind("job.toml:", 0), 0u) << grouped.petsc.location;

  EXPECT_NE(error_of(farm + "petsc_min_dofs = 0\n").find("farm.petsc_min_dofs"), std::string::npos);
  EXPECT_NE(error_of(farm + "petsc_min_factor_mib = 0\n").find("farm.petsc_min_factor_mib"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kValid) + "\n[farm]\npetsc_min_factor_mib = 100\n")
                .find("key 'farm.petsc_min_factor_mib' needs petsc_group_ranks"),
            std::string::npos);
  EXPECT_NE(error_of(replaced(farm, "= 2", "= -1")).find("farm.petsc_group_ranks"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kValid) + "\n[farm]\npetsc_groups = 2\n")
                .find("key 'farm.petsc_groups' needs petsc_group_ranks"),
            std::string::npos);
  EXPECT_NE(error_of(farm + "petsc_groups = 1000000\n").find("at most 1048576 ranks"),
            std::string::npos);
}

TEST(Job, EveryShippedJobReads) {
  int jobs = 0, bimanual = 0;
  for (const auto& entry : std::filesystem::directory_iterator(GRIP_JOBS_DIR)) {
    if (entry.path().extension() != ".toml") continue;
    ++jobs;
    const Job job = load_job(entry.path());
    EXPECT_EQ(job.name, entry.path().stem().string()) << entry.path();
    EXPECT_FALSE(list_objects(job).empty()) << entry.path();
    // The bimanual jobs (and only they) have two grippers per trial.
    const bool named_bimanual = job.name.rfind("bimanual-", 0) == 0;
    for (const GripperSetting& gripper : job.grippers) {
      EXPECT_EQ(gripper.bimanual, named_bimanual) << entry.path();
    }
    bimanual += named_bimanual;
  }
  EXPECT_GE(jobs, 8);
  EXPECT_EQ(bimanual, 2);
}

}  // namespace
}  // namespace grip::farm
