// PETSc's solves of real Newton systems (a soft cube squeezed by two pairs of soft pads) against
// CHOLMOD's, over two ranks and over one; a whole simulation through the hook; and a KSP held
// short of convergence reporting failure instead of a wrong answer.
#include <gtest/gtest.h>
#include <mpi.h>
#include <petscsys.h>

#include <functional>
#include <memory>

#include "bench/linear/bimanual_squeeze.hpp"
#include "bench/linear/newton_system.hpp"
#include "farm/petsc/petsc_session.hpp"
#include "farm/petsc/petsc_system_solver.hpp"
#include "solver/environment.hpp"
#include "solver/linear/sparse_cholesky.hpp"
#include "src/scene/invariants.hpp"

namespace grip::farm {
namespace {

// PETSc for the whole test program, initialized after main's MPI_Init.
class PetscEnvironment : public ::testing::Environment {
 public:
  void SetUp() override { session_ = std::make_unique<PetscSession>(std::vector<std::string>{}); }
  void TearDown() override { session_.reset(); }

 private:
  std::unique_ptr<PetscSession> session_;
};
[[maybe_unused]] ::testing::Environment* const petsc_environment =
    ::testing::AddGlobalTestEnvironment(new PetscEnvironment);

using Leader = std::function<void(const std::shared_ptr<PetscSystemSolver>&)>;

// A solver over `comm`: its rank 0 runs `leader` and then stops it, the other ranks serve.
void with_solver(MPI_Comm comm, const std::string& prefix, const Leader& leader) {
  auto petsc = std::make_shared<PetscSystemSolver>(comm, prefix);
  if (petsc->rank() == 0) {
    leader(petsc);
    petsc->stop();
  } else {
    petsc->serve();
  }
}

int world_rank() {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank;
}

// The squeeze at 1 cm cells (about 2,000 DOFs) after three steps of closing.
const bench::NewtonSystem& squeeze_system() {
  static const bench::NewtonSystem system =
      bench::capture_newton_system(bench::bimanual_squeeze(0.01), 3);
  return system;
}

// True when the matrix couples the cube's DOFs (the first body's, `cube_dofs` of them) to
// another body's: an active contact in the Newton system.
bool couples_cube_to_pads(const Eigen::SparseMatrix<double>& lower, int cube_dofs) {
  for (int c = 0; c < cube_dofs; ++c) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(lower, c); it; ++it) {
      if (it.row() >= cube_dofs) return true;
    }
  }
  return false;
}

// The relative tolerance the PETSc solution is held to against CHOLMOD's: the KSP stops at
// ||b - A x|| <= 1e-10 ||b||, which left 2e-12 to 5e-10 on the squeeze's systems.
constexpr double kRelativeTolerance = 1e-8;

void expect_matches_cholmod(MPI_Comm comm) {
  const bool leader = [&] {
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    return rank == 0;
  }();
  const bench::NewtonSystem* system = leader ? &squeeze_system() : nullptr;
  with_solver(comm, "", [&](const std::shared_ptr<PetscSystemSolver>& petsc) {
    const int cube_dofs =
        3 * static_cast<int>(bench::bimanual_squeeze(0.01).bodies[0].vertices.rows());
    ASSERT_TRUE(couples_cube_to_pads(system->lower, cube_dofs)) << "no contact in the system";
    solver::SparseCholesky cholesky;
    ASSERT_TRUE(cholesky.factorize(system->lower));
    const Eigen::VectorXd direct = cholesky.solve(system->rhs);
    Eigen::VectorXd x;
    ASSERT_TRUE(petsc->factorize(system->lower)) << petsc->failure();
    ASSERT_TRUE(petsc->solve(system->rhs, x)) << petsc->failure();
    EXPECT_EQ(petsc->method(), "cg + gamg/sor");  // grip's defaults
    EXPECT_GT(petsc->iterations(), 0);
    EXPECT_LE((x - direct).norm(), kRelativeTolerance * direct.norm()) << petsc->method();
    // The same pattern again with other values: only the values travel, and still match.
    Eigen::SparseMatrix<double> scaled = 2.0 * system->lower;
    ASSERT_TRUE(petsc->factorize(scaled)) << petsc->failure();
    ASSERT_TRUE(petsc->solve(system->rhs, x)) << petsc->failure();
    EXPECT_LE((2.0 * x - direct).norm(), kRelativeTolerance * direct.norm());
  });
}

TEST(PetscSystemSolver, MatchesCholmodOnTwoRanks) { expect_matches_cholmod(MPI_COMM_WORLD); }

TEST(PetscSystemSolver, MatchesCholmodOnOneRank) {
  if (world_rank() == 0) expect_matches_cholmod(MPI_COMM_SELF);
}

// How far apart two valid runs may end: Newton stops once the residual is below newton_tol
// times the standard weight (times h^2, in gradient units), so a converged iterate may sit up to
// residual / mass = newton_tol * g * h^2 from the exact one where only inertia resists (contact
// stiffness only brings it closer), and two runs up to twice that: 2e-6 m at dt = 10 ms, 2e-3 of
// d_hat. Measured: PETSc's run ends 1.2e-6 m from the direct one; two CHOLMOD runs that differ
// only in their fill-reducing ordering end 3e-9 m apart.
double position_tolerance(const solver::SimParameters& sim) {
  return 2.0 * sim.newton_tol * 9.81 * sim.dt * sim.dt;
}

TEST(PetscSystemSolver, SimulationThroughTheHookEqualsTheDirectOne) {
  constexpr int kSteps = 10;
  with_solver(MPI_COMM_WORLD, "", [&](const std::shared_ptr<PetscSystemSolver>& petsc) {
    // PETSc's iterative solve cannot tell an indefinite matrix, so Newton keeps every contact
    // Hessian projected through it; the direct run is asked for the same Newton.
    solver::SceneDescription scene = bench::bimanual_squeeze(0.01);
    scene.sim.projected_iterations = scene.sim.max_newton_iters;
    const auto model = solver::Model::build(scene);
    const double tolerance = position_tolerance(scene.sim);
    solver::Environment direct(model);
    solver::Environment iterative(model);
    iterative.use_linear_solver(petsc, 0);
    for (int s = 0; s < kSteps; ++s) {
      ASSERT_TRUE(direct.step()) << direct.failure();
      ASSERT_TRUE(iterative.step()) << iterative.failure();
      EXPECT_LE((iterative.dofs() - direct.dofs()).cwiseAbs().maxCoeff(), tolerance)
          << "step " << s;
      ASSERT_GT(iterative.last_step().min_distance, 0.0) << "step " << s;
      ASSERT_GT(iterative.last_step().min_volume_ratio, 0.0) << "step " << s;
      ASSERT_EQ(scene::count_intersections(iterative), 0) << "step " << s;
    }
    EXPECT_GT(petsc->iterations(), 0);                           // PETSc did solve
    EXPECT_EQ(iterative.last_step().contact_forces.size(), 4u);  // every pad presses on the cube
    const double newton_direct = static_cast<double>(direct.statistics().newton_iterations);
    EXPECT_NEAR(static_cast<double>(iterative.statistics().newton_iterations), newton_direct,
                0.1 * newton_direct);
  });
}

TEST(PetscSystemSolver, AKspThatDoesNotConvergeReportsFailure) {
  // One iteration is far too few for cg at 1e-10; the options database holds the cap.
  PetscOptionsSetValue(nullptr, "-capped_ksp_max_it", "1");
  with_solver(MPI_COMM_WORLD, "capped_", [&](const std::shared_ptr<PetscSystemSolver>& petsc) {
    const bench::NewtonSystem& system = squeeze_system();
    Eigen::VectorXd x;
    ASSERT_TRUE(petsc->factorize(system.lower)) << petsc->failure();
    EXPECT_FALSE(petsc->solve(system.rhs, x));
    EXPECT_NE(petsc->failure().find("DIVERGED_ITS"), std::string::npos) << petsc->failure();
    // An environment fails with that reason rather than taking a wrong step.
    solver::Environment env(solver::Model::build(bench::bimanual_squeeze(0.01)));
    env.use_linear_solver(petsc, 0);
    EXPECT_FALSE(env.step());
    EXPECT_NE(env.failure().find("DIVERGED_ITS"), std::string::npos) << env.failure();
  });
  PetscOptionsClearValue(nullptr, "-capped_ksp_max_it");
}

TEST(PetscSystemSolver, SystemsBelowTheThresholdStayWithTheDirectSolve) {
  with_solver(MPI_COMM_WORLD, "", [&](const std::shared_ptr<PetscSystemSolver>& petsc) {
    const auto model = solver::Model::build(bench::bimanual_squeeze(0.01));
    solver::Environment direct(model);
    solver::Environment hooked(model);
    hooked.use_linear_solver(petsc, model->dof_count() + 1);
    for (int s = 0; s < 3; ++s) {
      ASSERT_TRUE(direct.step()) << direct.failure();
      ASSERT_TRUE(hooked.step()) << hooked.failure();
      ASSERT_EQ(hooked.dofs(), direct.dofs()) << "step " << s;  // bit for bit: CHOLMOD's solves
    }
    EXPECT_EQ(petsc->iterations(), 0);  // PETSc never solved
  });
}

}  // namespace
}  // namespace grip::farm
