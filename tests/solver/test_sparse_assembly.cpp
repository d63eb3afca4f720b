// Pattern reuse gives exactly the matrix a fresh assembly gives, and rebuilds only on change.
#include <gtest/gtest.h>

#include <algorithm>
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

long long fresh_pattern_size(int n, const std::vector<Eigen::Triplet<double>>& triplets) {
  Eigen::SparseMatrix<double> m(n, n);
  m.setFromTriplets(triplets.begin(), triplets.end());
  return m.nonZeros();
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

// A contact's entries at the end of the list: once in the pattern, a contact that goes (its
// entries stay as explicit zeros) and comes back costs no new pattern; the values are always the
// fresh matrix's.
TEST(SparseAssembly, AContactThatGoesAndComesBackCostsNoNewPattern) {
  SparseAssembly assembly;
  const int n = 40;
  const auto elements = random_triplets(n, 300, 7, 1);
  auto with_contact = elements;
  for (const auto& t : random_triplets(n, 20, 8, 2)) with_contact.push_back(t);
  const std::vector<Eigen::Triplet<double>>* order[] = {&with_contact, &elements, &with_contact,
                                                        &elements};
  for (const auto* triplets : order) {
    const Eigen::MatrixXd assembled(assembly.assemble(n, *triplets));
    EXPECT_EQ((assembled - fresh(n, *triplets)).norm(), 0.0);
  }
  EXPECT_EQ(assembly.pattern_builds(), 1);
  EXPECT_GT(assembly.assemble(n, elements).nonZeros(), fresh_pattern_size(n, elements));
}

// Contacts that keep coming at new places grow the pattern; past a fifth more than its last
// fresh build, it is built fresh, without the stale entries.
TEST(SparseAssembly, APatternGrownTooFarIsBuiltFresh) {
  SparseAssembly assembly;
  const int n = 60;
  const auto elements = random_triplets(n, 200, 7, 1);
  long long largest = 0;
  for (unsigned contact = 1; contact <= 12; ++contact) {
    auto triplets = elements;
    for (const auto& t : random_triplets(n, 30, 100 + contact, 2)) triplets.push_back(t);
    const Eigen::SparseMatrix<double>& m = assembly.assemble(n, triplets);
    EXPECT_EQ((Eigen::MatrixXd(m) - fresh(n, triplets)).norm(), 0.0) << "contact " << contact;
    largest = std::max<long long>(largest, m.nonZeros());
  }
  const long long first = fresh_pattern_size(n, [&] {
    auto triplets = elements;
    for (const auto& t : random_triplets(n, 30, 101, 2)) triplets.push_back(t);
    return triplets;
  }());
  EXPECT_GT(largest, first);
  EXPECT_LE(largest, first + first / 5 + 60);  // at most one growth past the limit
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
