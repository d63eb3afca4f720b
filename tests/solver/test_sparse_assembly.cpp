// Pattern reuse gives exactly the matrix a fresh assembly gives, and rebuilds only on change.
#include <gtest/gtest.h>

#include <random>

#include "solver/linear/sparse_assembly.hpp"

namespace grip::solver {
namespace {

std::vector<Eigen::Triplet<double>> random_triplets(int n, int count, unsigned pattern_seed,
                                                    unsigned value_seed) {
  std::mt19937 pattern(pattern_seed);
  std::mt19937 values(value_seed);
  std::uniform_int_distribution<int> index(0, n - 1);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<Eigen::Triplet<double>> triplets;
  for (int i = 0; i < count; ++i) {
    const int a = index(pattern), b = index(pattern);
    triplets.emplace_back(std::max(a, b), std::min(a, b), value(values));  // duplicates too
  }
  return triplets;
}

Eigen::MatrixXd fresh(int n, const std::vector<Eigen::Triplet<double>>& triplets) {
  Eigen::SparseMatrix<double> m(n, n);
  m.setFromTriplets(triplets.begin(), triplets.end());
  return Eigen::MatrixXd(m);
}

TEST(SparseAssembly, ReusedPatternGivesTheFreshMatrix) {
  SparseAssembly assembly;
  const int n = 40;
  for (unsigned values = 1; values <= 5; ++values) {
    const auto triplets = random_triplets(n, 300, 7, values);
    const Eigen::MatrixXd assembled(assembly.assemble(n, triplets));
    EXPECT_EQ((assembled - fresh(n, triplets)).norm(), 0.0) << "values " << values;
  }
  EXPECT_EQ(assembly.pattern_builds(), 1);
}

TEST(SparseAssembly, ANewPatternIsBuiltAgain) {
  SparseAssembly assembly;
  const int n = 30;
  assembly.assemble(n, random_triplets(n, 200, 1, 1));
  const auto other = random_triplets(n, 200, 2, 1);
  const Eigen::MatrixXd assembled(assembly.assemble(n, other));
  EXPECT_EQ((assembled - fresh(n, other)).norm(), 0.0);
  auto longer = other;
  longer.emplace_back(n - 1, 0, 2.5);
  const Eigen::MatrixXd grown(assembly.assemble(n, longer));
  EXPECT_EQ((grown - fresh(n, longer)).norm(), 0.0);
  EXPECT_EQ(assembly.pattern_builds(), 3);
}

// Fixed DOFs' rows and columns are left out and their diagonals are 1, as an elimination of
// prescribed DOFs by hand gives; a new set of fixed DOFs is a new pattern.
TEST(SparseAssembly, FixedDofsAreEliminatedWithAUnitDiagonal) {
  SparseAssembly assembly;
  const int n = 40;
  const auto eliminated = [&](const std::vector<Eigen::Triplet<double>>& triplets,
                              const std::vector<char>& fixed) {
    std::vector<Eigen::Triplet<double>> kept;
    for (const auto& t : triplets) {
      if (!fixed[t.row()] && !fixed[t.col()]) kept.push_back(t);
    }
    for (int i = 0; i < n; ++i) {
      if (fixed[i]) kept.emplace_back(i, i, 1.0);
    }
    return fresh(n, kept);
  };
  std::vector<char> fixed(n, 0);
  for (int i = 0; i < n; i += 7) fixed[i] = 1;
  for (unsigned values = 1; values <= 4; ++values) {
    const auto triplets = random_triplets(n, 300, 7, values);
    const Eigen::MatrixXd assembled(assembly.assemble(n, triplets, fixed));
    EXPECT_EQ((assembled - eliminated(triplets, fixed)).norm(), 0.0) << "values " << values;
    EXPECT_EQ(assembled(7, 7), 1.0);
    EXPECT_EQ(assembled.row(7).cwiseAbs().sum(), 1.0);
  }
  EXPECT_EQ(assembly.pattern_builds(), 1);
  fixed[1] = 1;
  const auto triplets = random_triplets(n, 300, 7, 9);
  const Eigen::MatrixXd assembled(assembly.assemble(n, triplets, fixed));
  EXPECT_EQ((assembled - eliminated(triplets, fixed)).norm(), 0.0);
  EXPECT_EQ(assembly.pattern_builds(), 2);
}

}  // namespace
}  // namespace grip::solver
