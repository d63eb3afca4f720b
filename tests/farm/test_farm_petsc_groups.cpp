// The job's PETSc groups ([farm] petsc_group_ranks) as a user runs them: a soft bimanual job
// whose Newton systems all go to PETSc (the group forced on with petsc_min_dofs = 1) gives the
// verdicts CHOLMOD gives, with trajectories within 1e-6 m, on 1 rank without mpirun (a group of
// one), on 2 ranks (one group: rank 0 leads, rank 1 serves) and on 3 (rank 0 alone beside a
// group of ranks 1 and 2); a group larger than the run, and PETSc options without a group, are
// refused before any work. Which models go to a group: by their CHOLMOD factor's size (the
// default rule) or by their DOFs.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "io/dataset_reader.hpp"
#include "tests/app/run_grip.hpp"
#include "tests/farm/farm_test_job.hpp"

namespace grip::farm {
namespace {

namespace fs = std::filesystem;
using grip::testing::quoted;

class FarmPetscGroups : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("grip_farm_petsc_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    ::setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
    ::setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // `grip farm` on `ranks` ranks (0: without mpirun); its exit status, stderr in `err`.
  int farm(const std::string& job, int ranks, const std::string& name, std::string& err,
           const std::string& after = "") {
    testing::write_file(dir_ / (name + ".toml"), job);
    const std::string launcher = ranks > 0 ? std::string(GRIP_MPIEXEC) + " --oversubscribe -np " +
                                                 std::to_string(ranks) + " "
                                           : "";
    const std::string command =
        launcher + GRIP_EXECUTABLE + " farm " + quoted(dir_ / (name + ".toml")) + " --output " +
        quoted(dir_ / (name + ".h5")) + " --threads 1 --batch 1 --report " +
        quoted(dir_ / (name + ".json")) + after + " >/dev/null 2>" + quoted(dir_ / "err.txt");
    const int status = std::system(command.c_str());
    err = grip::testing::slurp(dir_ / "err.txt");
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }

  nlohmann::json report(const std::string& name) {
    std::ifstream in(dir_ / (name + ".json"));
    return nlohmann::json::parse(in);
  }

  fs::path dir_;
};

double largest_difference(const std::vector<float>& a, const std::vector<float>& b) {
  EXPECT_EQ(a.size(), b.size());
  double largest = 0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    largest = std::max(largest, std::abs(static_cast<double>(a[i]) - b[i]));
  }
  return largest;
}

// The same verdicts, and every frame's object and gripper vertices within `tolerance` (m).
void expect_same_within(const fs::path& a, const fs::path& b, double tolerance) {
  const io::DatasetReader ra(a), rb(b);
  const std::vector<io::CandidateRecord> ca = ra.candidates(), cb = rb.candidates();
  ASSERT_EQ(ca.size(), cb.size());
  for (std::size_t i = 0; i < ca.size(); ++i) {
    EXPECT_EQ(ca[i].status, cb[i].status) << "candidate " << i;
    EXPECT_EQ(ca[i].failure, cb[i].failure) << "candidate " << i;
    const std::optional<io::TrajectoryRecord> ta = ra.trajectory(i), tb = rb.trajectory(i);
    ASSERT_TRUE(ta && tb) << "candidate " << i;
    const double object = largest_difference(ta->object_vertices, tb->object_vertices);
    const double gripper = largest_difference(ta->gripper_vertices, tb->gripper_vertices);
    EXPECT_LE(object, tolerance) << "candidate " << i << ", " << a << " against " << b;
    EXPECT_LE(gripper, tolerance) << "candidate " << i << ", " << a << " against " << b;
    std::printf("candidate %zu: %s, vertices within %.3g m (object) and %.3g m (grippers)\n", i,
                std::string(io::to_string(ca[i].status)).c_str(), object, gripper);
  }
}

// Both solve every Newton system to round-off: CHOLMOD without CG on earlier factorizations.
const std::string kExactSolves = "\n[physics]\nreuse_iterations = 0\n";

TEST_F(FarmPetscGroups, ForcedOnGivesCholmodsVerdictsAndTrajectoriesWithinOneMicrometre) {
  std::string err;
  ASSERT_EQ(farm(testing::bimanual_soft_job(2, "") + kExactSolves, 0, "cholmod", err), 0) << err;
  EXPECT_EQ(report("cholmod")["petsc_solves"], 0);
  // 0: without mpirun, one rank leading a group of one (PETSc on its own rank).
  for (const int ranks : {0, 2, 3}) {
    const std::string forced =
        "petsc_group_ranks = " + std::to_string(ranks == 0 ? 1 : 2) + "\npetsc_min_dofs = 1\n";
    const std::string name = "petsc" + std::to_string(ranks);
    ASSERT_EQ(farm(testing::bimanual_soft_job(2, forced) + kExactSolves, ranks, name, err), 0)
        << err;
    const nlohmann::json r = report(name);
    EXPECT_EQ(r["petsc_groups"], 1);
    EXPECT_GT(r["petsc_solves"].get<long>(), 100) << "the group solved no Newton system";
    EXPECT_EQ(r["done"], 2);
    expect_same_within(dir_ / "cholmod.h5", dir_ / (name + ".h5"), 1e-6);
  }
}

// The default rule: a model goes to the group by the size of CHOLMOD's factor of its
// contact-free pattern. The job's soft cylinder and fingers need far less than a MiB; the
// leader's CHOLMOD keeps them under the default and any larger budget, the group takes them
// under a budget below their factor, and the DOF rule takes them whatever the budget.
TEST_F(FarmPetscGroups, ModelsGoToTheGroupByTheirFactorsSizeOrByDofs) {
  std::string err;
  const std::string group = "petsc_group_ranks = 1\n";
  const std::vector<std::pair<std::string, bool>> rules = {
      {"", false},
      {"petsc_min_factor_mib = 0.001\n", true},
      {"petsc_min_factor_mib = 1000000\n", false},
      {"petsc_min_factor_mib = 1000000\npetsc_min_dofs = 1\n", true}};
  for (std::size_t i = 0; i < rules.size(); ++i) {
    const auto& [rule, to_group] = rules[i];
    const std::string name = "rule" + std::to_string(i);
    ASSERT_EQ(farm(testing::bimanual_soft_job(1, group + rule), 0, name, err), 0) << err;
    const nlohmann::json r = report(name);
    EXPECT_EQ(r["done"], 1) << rule;
    if (to_group) {
      EXPECT_GT(r["petsc_solves"].get<long>(), 10) << rule;
    } else {
      EXPECT_EQ(r["petsc_solves"], 0) << rule;
    }
  }
}

// The rule decides per (object, gripper) model, and only a group's leader runs the trials of a
// model the rule sends to its group: a plain rank never hands such a system to its own CHOLMOD.
// A soft and a rigid cylinder under mpirun -np 2, a group of one on rank 1, the DOF rule
// between the two models (the rigid model's two jaws and affine body have 36 DOFs, the soft
// one some 1,300): every Newton iteration of a soft trial went to PETSc, whichever rank
// claimed first, and no rigid one did.
TEST_F(FarmPetscGroups, OnlyALeaderRunsTheTrialsTheRuleSendsToItsGroup) {
  std::string err;
  std::string job = testing::bimanual_soft_job(
      2, "petsc_group_ranks = 1\npetsc_min_dofs = 1000\npetsc_min_factor_mib = 1000000\n");
  const std::string soft = "tet_edge = 0.01\n";  // the soft cylinder's last line
  job.replace(job.find(soft), soft.size(), soft + "\n[[objects]]\ncategory = \"cylinder\"\n");
  ASSERT_EQ(farm(job, 2, "mixed", err), 0) << err;
  const nlohmann::json r = report("mixed");
  EXPECT_EQ(r["done"], 4);
  const io::DatasetReader reader(dir_ / "mixed.h5");
  const io::DatasetLayout& layout = reader.layout();
  long soft_iterations = 0, soft_steps = 0, rigid_iterations = 0;
  for (const io::CandidateRecord& c : reader.candidates()) {
    const bool soft_object = layout.objects[layout.object[c.id]].tets > 0;
    (soft_object ? soft_iterations : rigid_iterations) += c.newton.iterations;
    if (soft_object) soft_steps += c.newton.steps;
  }
  ASSERT_GT(soft_iterations, soft_steps);
  ASSERT_GT(rigid_iterations, 0);
  const long solves = r["petsc_solves"].get<long>();
  // Every Newton iteration solves a system but a step's last, whose residual may already have
  // converged; a retried step's discarded ones add.
  EXPECT_GE(solves, soft_iterations - soft_steps);
  EXPECT_LT(solves, soft_iterations + rigid_iterations);
}

TEST_F(FarmPetscGroups, AGroupLargerThanTheRunIsRefusedBeforeAnyWork) {
  std::string err;
  const std::string job =
      testing::bimanual_soft_job(2, "petsc_group_ranks = 2\npetsc_groups = 2\n");
  EXPECT_EQ(farm(job, 3, "big", err), 1);
  EXPECT_NE(err.find("big.toml:"), std::string::npos) << err;
  EXPECT_NE(err.find("key 'farm.petsc_group_ranks' asks for 2 groups of 2 rank(s), 4 in all, "
                     "but this run has 3 rank(s)"),
            std::string::npos)
      << err;
  EXPECT_FALSE(fs::exists(dir_ / "big.h5"));

  EXPECT_EQ(farm(testing::bimanual_soft_job(2, ""), 0, "options", err, " -- -ksp_rtol 1e-12"), 1);
  EXPECT_NE(err.find("PETSc options were given after '--', but the job has no PETSc group"),
            std::string::npos)
      << err;
  EXPECT_FALSE(fs::exists(dir_ / "options.h5"));
}

}  // namespace
}  // namespace grip::farm
