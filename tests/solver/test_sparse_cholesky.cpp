// CHOLMOD solves: correct answers, one symbolic analysis per pattern, honest failure on
// matrices that are not positive definite; the factor's size from the symbolic analysis alone,
// exact against analytic fill and against the numeric factor, also for a model's contact-free
// pattern; CG on an earlier factorization, alone and as Newton uses it.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <numeric>
#include <random>
#include <vector>

#include "solver/linear/sparse_cholesky.hpp"
#include "tests/solver/scene_builders.hpp"

namespace grip::solver {
namespace {

// Lower triangle of an nx x ny x nz grid Laplacian (7-point stencil) times `scale` plus
// `shift` * I: symmetric positive definite for shift > 0, with the fill pattern of a tet-mesh
// system.
Eigen::SparseMatrix<double> grid_system(int nx, int ny, int nz, double scale, double shift) {
  const int size = nx * ny * nz;
  auto id = [ny, nz](int i, int j, int k) { return (i * ny + j) * nz + k; };
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j)
      for (int k = 0; k < nz; ++k) {
        const int row = id(i, j, k);
        entries.emplace_back(row, row, 6.0 * scale + shift);
        if (i + 1 < nx) entries.emplace_back(id(i + 1, j, k), row, -scale);
        if (j + 1 < ny) entries.emplace_back(id(i, j + 1, k), row, -scale);
        if (k + 1 < nz) entries.emplace_back(id(i, j, k + 1), row, -scale);
      }
  Eigen::SparseMatrix<double> lower(size, size);
  lower.setFromTriplets(entries.begin(), entries.end());
  lower.makeCompressed();
  return lower;
}

Eigen::SparseMatrix<double> grid_system(int n, double scale, double shift) {
  return grid_system(n, n, n, scale, shift);
}

Eigen::VectorXd random_vector(Eigen::Index size, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::VectorXd v(size);
  for (Eigen::Index i = 0; i < size; ++i) v[i] = uniform(rng);
  return v;
}

double relative_residual(const Eigen::SparseMatrix<double>& lower, const Eigen::VectorXd& x,
                         const Eigen::VectorXd& b) {
  const Eigen::VectorXd ax = lower.selfadjointView<Eigen::Lower>() * x;
  return (ax - b).norm() / b.norm();
}

class SparseCholeskyOrdering : public ::testing::TestWithParam<SparseCholesky::Ordering> {};

TEST_P(SparseCholeskyOrdering, SolvesAGridSystem) {
  SparseCholesky cholesky(GetParam());
  const auto lower = grid_system(12, 1.0, 1e-3);
  const Eigen::VectorXd b = random_vector(lower.rows(), 1);
  ASSERT_TRUE(cholesky.factorize(lower));
  EXPECT_LT(relative_residual(lower, cholesky.solve(b), b), 1e-10);
}

TEST_P(SparseCholeskyOrdering, ReusesTheAnalysisWhileThePatternHolds) {
  SparseCholesky cholesky(GetParam());
  const Eigen::VectorXd b = random_vector(8 * 8 * 8, 2);
  for (int iteration = 0; iteration < 4; ++iteration) {
    const auto lower = grid_system(8, 1.0 + iteration, 0.5 * iteration + 0.1);
    ASSERT_TRUE(cholesky.factorize(lower));
    EXPECT_LT(relative_residual(lower, cholesky.solve(b), b), 1e-10);
  }
  EXPECT_EQ(cholesky.analyses(), 1);

  // A new pattern (a coupling entry added, as a new contact does) is analysed once more.
  auto coupled = grid_system(8, 1.0, 0.1);
  coupled.coeffRef(200, 3) = -0.01;
  coupled.makeCompressed();
  ASSERT_TRUE(cholesky.factorize(coupled));
  EXPECT_LT(relative_residual(coupled, cholesky.solve(b), b), 1e-10);
  EXPECT_EQ(cholesky.analyses(), 2);
}

TEST_P(SparseCholeskyOrdering, ReportsAnIndefiniteMatrix) {
  SparseCholesky cholesky(GetParam());
  auto lower = grid_system(6, 1.0, 1e-3);
  lower.coeffRef(17, 17) = -5.0;
  EXPECT_FALSE(cholesky.factorize(lower));
}

INSTANTIATE_TEST_SUITE_P(Orderings, SparseCholeskyOrdering,
                         ::testing::Values(SparseCholesky::Ordering::kMetis,
                                           SparseCholesky::Ordering::kAmd));

TEST(SparseCholesky, SolvesANearbyMatrixByConjugateGradientsOnAnEarlierFactorization) {
  SparseCholesky cholesky;
  const auto earlier = grid_system(10, 1.0, 0.1);
  const Eigen::VectorXd b = random_vector(earlier.rows(), 4);
  Eigen::VectorXd x;
  int iterations = -1;
  EXPECT_FALSE(cholesky.solve_preconditioned(earlier, b, 1e-8, 50, x, iterations))
      << "no factorization to precondition with";
  ASSERT_TRUE(cholesky.factorize(earlier));
  ASSERT_TRUE(cholesky.solve_preconditioned(earlier, b, 1e-8, 50, x, iterations));
  EXPECT_EQ(iterations, 1) << "the factorized matrix itself";
  EXPECT_LT(relative_residual(earlier, x, b), 1e-8);

  // Stiffer on 20 DOFs, as new contacts make a Newton matrix: the preconditioned matrix is the
  // identity but for a rank-20 change, so CG gets there in about 21 iterations.
  auto nearby = earlier;
  for (int i = 0; i < 20; ++i) nearby.coeffRef(37 * i, 37 * i) += 5.0;
  ASSERT_TRUE(cholesky.solve_preconditioned(nearby, b, 1e-8, 50, x, iterations));
  EXPECT_LT(relative_residual(nearby, x, b), 1e-8);
  EXPECT_GT(iterations, 2);
  EXPECT_LE(iterations, 25);
  EXPECT_FALSE(cholesky.solve_preconditioned(nearby, b, 1e-8, 2, x, iterations));
  EXPECT_EQ(iterations, 2);
  // The factorization is kept: a direct solve is still the earlier matrix's.
  EXPECT_LT(relative_residual(earlier, cholesky.solve(b), b), 1e-10);

  const auto other_size = grid_system(9, 1.0, 0.1);
  EXPECT_FALSE(cholesky.solve_preconditioned(other_size, random_vector(other_size.rows(), 5), 1e-8,
                                             50, x, iterations));
  auto indefinite = earlier;
  indefinite.coeffRef(17, 17) = -5.0;
  ASSERT_FALSE(cholesky.factorize(indefinite));
  EXPECT_FALSE(cholesky.solve_preconditioned(earlier, b, 1e-8, 50, x, iterations))
      << "a failed factorization preconditions nothing";
}

// CG's preconditioner solves a thin slab's factor (small supernodes, as a fin-ray finger's) on
// its simplicial copy, and agrees with the supernodal solve to round-off; the copy is made
// afresh after each factorization (a second matrix of the same pattern is solved as itself, not
// as the first). A cube's factor (large supernodes, as with a soft object's tets) is solved as
// it is, and so is a small simplicial one.
TEST(SparseCholesky, PreconditionsOnASimplicialCopyWhereTheSupernodesAreSmall) {
  SparseCholesky cholesky;
  const Eigen::VectorXd b = random_vector(60 * 60 * 2, 6);
  for (const double shift : {1e-3, 2.0}) {
    const auto slab = grid_system(60, 60, 2, 1.0, shift);
    ASSERT_TRUE(cholesky.factorize(slab));
    ASSERT_TRUE(cholesky.preconditions_on_simplicial_copy());
    const Eigen::VectorXd supernodal = cholesky.solve(b);
    const Eigen::VectorXd copy = cholesky.precondition(b);
    EXPECT_LT(relative_residual(slab, copy, b), 1e-10) << shift;
    EXPECT_LT((copy - supernodal).norm(), 1e-12 * supernodal.norm()) << shift;
    EXPECT_EQ(cholesky.precondition(b), copy) << "the kept copy solves the same";
  }
  EXPECT_EQ(cholesky.analyses(), 1);
  const auto cube = grid_system(24, 1.0, 0.1);
  ASSERT_TRUE(cholesky.factorize(cube));
  EXPECT_FALSE(cholesky.preconditions_on_simplicial_copy());
  const Eigen::VectorXd c = random_vector(cube.rows(), 7);
  EXPECT_EQ(cholesky.precondition(c), cholesky.solve(c));
  const auto small = grid_system(4, 1.0, 0.1);
  ASSERT_TRUE(cholesky.factorize(small));
  EXPECT_FALSE(cholesky.preconditions_on_simplicial_copy());
  const Eigen::VectorXd d = random_vector(small.rows(), 8);
  EXPECT_LT(relative_residual(small, cholesky.precondition(d), d), 1e-12);
}

TEST(SparseCholesky, OrderingsAgree) {
  const auto lower = grid_system(10, 2.0, 0.01);
  const Eigen::VectorXd b = random_vector(lower.rows(), 3);
  SparseCholesky metis(SparseCholesky::Ordering::kMetis);
  SparseCholesky amd(SparseCholesky::Ordering::kAmd);
  ASSERT_TRUE(metis.factorize(lower));
  ASSERT_TRUE(amd.factorize(lower));
  EXPECT_LT((metis.solve(b) - amd.solve(b)).norm() / amd.solve(b).norm(), 1e-10);
}

// The compressed lower pattern of a star: vertex 0 is the hub, coupled to every leaf.
void star_pattern(int n, std::vector<int>& outer, std::vector<int>& inner) {
  outer = {0};
  inner.clear();
  for (int col = 0; col < n; ++col) {
    inner.push_back(col);
    if (col == 0) {
      for (int leaf = 1; leaf < n; ++leaf) inner.push_back(leaf);
    }
    outer.push_back(static_cast<int>(inner.size()));
  }
}

TEST(SparseCholesky, SymbolicFactorSizeIsTheAnalyticFillOfAStar) {
  const int n = 200;
  std::vector<int> outer, inner;
  star_pattern(n, outer, inner);
  std::vector<int> hub_last(n);
  std::iota(hub_last.begin(), hub_last.end(), 1);
  hub_last.back() = 0;
  // Hub last: each leaf's column holds itself and the hub, no fill.
  EXPECT_EQ(symbolic_factor_bytes(n, outer, inner, hub_last), (2 * n - 1) * sizeof(double));
  // Hub first: eliminating it couples every leaf to every other, a dense triangle (supernodal,
  // so CHOLMOD may pad it; never less than the triangle).
  std::vector<int> hub_first(n);
  std::iota(hub_first.begin(), hub_first.end(), 0);
  EXPECT_GE(symbolic_factor_bytes(n, outer, inner, hub_first),
            static_cast<std::size_t>(n) * (n + 1) / 2 * sizeof(double));
  EXPECT_THROW(symbolic_factor_bytes(n, outer, inner, std::vector<int>(n - 1)),
               std::invalid_argument);
}

TEST(SparseCholesky, SymbolicFactorSizeIsTheNumericFactorsSize) {
  for (const int n : {4, 14}) {  // simplicial and supernodal
    const auto lower = grid_system(n, 1.0, 0.1);
    auto order = std::make_shared<std::vector<int>>(lower.rows());
    std::iota(order->rbegin(), order->rend(), 0);  // reversed: any fixed permutation will do
    SparseCholesky cholesky(order);
    ASSERT_TRUE(cholesky.factorize(lower));
    const std::vector<int> outer(lower.outerIndexPtr(), lower.outerIndexPtr() + lower.cols() + 1);
    const std::vector<int> inner(lower.innerIndexPtr(), lower.innerIndexPtr() + lower.nonZeros());
    EXPECT_EQ(symbolic_factor_bytes(static_cast<int>(lower.rows()), outer, inner, *order),
              cholesky.factor_bytes())
        << n;
    EXPECT_GT(cholesky.factor_bytes(), lower.nonZeros() * sizeof(double)) << n;  // it fills in
  }
}

// Keeps the first system's factor size, solving by the model's own ordering as the
// environment does.
class FactorSizeRecorder final : public LinearSystemSolver {
 public:
  explicit FactorSizeRecorder(const Model& model) : cholesky_(model.ordering()) {}
  bool factorize(const Eigen::SparseMatrix<double>& lower) override {
    const bool ok = cholesky_.factorize(lower);
    if (first_bytes_ == 0) first_bytes_ = cholesky_.factor_bytes();
    return ok;
  }
  bool solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& x) override {
    return cholesky_.solve(rhs, x);
  }
  std::string failure() const override { return cholesky_.failure(); }
  bool refuses_indefinite() const override { return true; }
  std::size_t first_bytes() const { return first_bytes_; }

 private:
  SparseCholesky cholesky_;
  std::size_t first_bytes_ = 0;
};

TEST(SparseCholesky, AModelsContactFreeFactorSizeIsItsFirstSystemsFactor) {
  // Two soft boxes apart, one of them pinned by a face to a kinematic plate, and an affine box:
  // free, prescribed and 12-DOF blocks, no contact in the first step.
  SceneDescription scene;
  scene.bodies.push_back(testing::soft_box("free", Eigen::Vector3d(0.04, 0.03, 0.02), 0.005,
                                           Eigen::Vector3d::Zero(), 1e5));
  BodyDescription pinned = testing::soft_box("pinned", Eigen::Vector3d(0.03, 0.03, 0.03), 0.006,
                                             Eigen::Vector3d(0.2, 0.0, 0.0), 1e6);
  scene.bodies.push_back(testing::rigid_box("plate", BodyType::kKinematic,
                                            Eigen::Vector3d(0.05, 0.05, 0.005),
                                            Eigen::Vector3d(0.2, 0.0, 0.02)));
  Pin pin;
  pin.kinematic_body = 1;
  for (Eigen::Index v = 0; v < pinned.vertices.rows(); ++v) {
    if (pinned.vertices(v, 2) > 0.0149) pin.vertices.push_back(static_cast<int>(v));
  }
  ASSERT_FALSE(pin.vertices.empty());
  pinned.pins = {pin};
  scene.bodies.push_back(pinned);
  scene.bodies.push_back(testing::rigid_box("affine", BodyType::kAffine,
                                            Eigen::Vector3d::Constant(0.02),
                                            Eigen::Vector3d(-0.2, 0.0, 0.0)));
  Environment env(Model::build(scene));
  auto recorder = std::make_shared<FactorSizeRecorder>(env.model());
  env.use_linear_solver(recorder, 0);
  ASSERT_TRUE(env.step()) << env.failure();
  EXPECT_GT(recorder->first_bytes(), 0u);
  EXPECT_EQ(env.model().contact_free_factor_bytes(), recorder->first_bytes());
}

// A soft box dropped onto a plate, and left to rest on it: most Newton systems are solved by CG
// on an earlier factorization, and where it falls and where it rests are the exact solves'.
TEST(NewtonSolver, SolvesOnEarlierFactorizationsWithoutChangingTheAnswer) {
  SceneDescription scene;
  scene.sim.gravity = Eigen::Vector3d(0.0, 0.0, -9.81);
  scene.bodies.push_back(testing::rigid_box("plate", BodyType::kKinematic,
                                            Eigen::Vector3d(0.1, 0.1, 0.01),
                                            Eigen::Vector3d(0.0, 0.0, -0.005)));
  scene.bodies.push_back(testing::soft_box("soft", Eigen::Vector3d(0.04, 0.04, 0.04), 0.004,
                                           Eigen::Vector3d(0.0, 0.0, 0.0225), 1e5));
  Environment reusing(Model::build(scene));
  Environment exact(Model::build(scene));
  // A solver other than the environment's own Cholesky: every system factorized.
  exact.use_linear_solver(std::make_shared<SparseCholesky>(exact.model().ordering()), 0);
  for (int s = 0; s < 40; ++s) {
    ASSERT_TRUE(reusing.step()) << reusing.failure();
    ASSERT_TRUE(exact.step()) << exact.failure();
    ASSERT_GT(reusing.last_step().min_distance, 0.0) << "step " << s;
    ASSERT_GT(reusing.last_step().min_volume_ratio, 0.0) << "step " << s;
  }
  const LinearSolveCounts& counts = reusing.linear_solves();
  EXPECT_GT(counts.reused, counts.factorizations);
  EXPECT_EQ(exact.linear_solves().reused, 0);
  const Vertices box = exact.body_vertices(1);
  EXPECT_LT(box.col(2).minCoeff(), 1e-3) << "the box fell onto the plate";
  EXPECT_GT(box.col(2).minCoeff(), 0.0);
  const double largest_difference = (reusing.body_vertices(1) - box).cwiseAbs().maxCoeff();
  EXPECT_LT(largest_difference, 1e-6) << "m";
  std::printf(
      "reused %ld, factorizations %ld, CG iterations %ld; exact %ld factorizations; "
      "largest difference %.3g m\n",
      counts.reused, counts.factorizations, counts.cg_iterations,
      exact.linear_solves().factorizations, largest_difference);
}

}  // namespace
}  // namespace grip::solver
