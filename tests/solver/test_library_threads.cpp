// CHOLMOD's supernodal factorization runs on the calling thread alone: its OpenMP loops ask for
// a team of a size fixed when CHOLMOD was compiled, and grip runs environments on threads of
// its own (--threads). Its own binary: a thread pool started by an earlier test would hide one
// started here.
#include <dirent.h>
#include <gtest/gtest.h>

#include <vector>

#include "solver/linear/blas_threads.hpp"
#include "solver/linear/sparse_cholesky.hpp"

namespace grip::solver {
namespace {

int thread_count() {
  DIR* tasks = opendir("/proc/self/task");
  int count = 0;
  while (const dirent* entry = readdir(tasks)) count += entry->d_name[0] != '.';
  closedir(tasks);
  return count;
}

// Lower triangle of a 3D grid Laplacian plus the identity, 3 DOFs a grid point: its
// supernodes are far larger than the 1,024 entries past which CHOLMOD's loops go parallel.
Eigen::SparseMatrix<double> grid_system(int n) {
  auto id = [n](int i, int j, int k, int d) { return 3 * ((i * n + j) * n + k) + d; };
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
        for (int d = 0; d < 3; ++d) {
          const int row = id(i, j, k, d);
          entries.emplace_back(row, row, 7.0);
          if (i + 1 < n) entries.emplace_back(id(i + 1, j, k, d), row, -1.0);
          if (j + 1 < n) entries.emplace_back(id(i, j + 1, k, d), row, -1.0);
          if (k + 1 < n) entries.emplace_back(id(i, j, k + 1, d), row, -1.0);
        }
  const int size = 3 * n * n * n;
  Eigen::SparseMatrix<double> lower(size, size);
  lower.setFromTriplets(entries.begin(), entries.end());
  lower.makeCompressed();
  return lower;
}

TEST(LibraryThreads, ASupernodalFactorizationStartsNoThread) {
  use_single_threaded_blas();  // as every environment does first
  const Eigen::SparseMatrix<double> lower = grid_system(20);
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(lower.rows());
  const int before = thread_count();
  SparseCholesky cholesky(SparseCholesky::Ordering::kMetis);
  ASSERT_TRUE(cholesky.factorize(lower));
  const Eigen::VectorXd x = cholesky.solve(b);
  EXPECT_LT((lower.selfadjointView<Eigen::Lower>() * x - b).norm() / b.norm(), 1e-12);
  EXPECT_EQ(thread_count(), before);
}

}  // namespace
}  // namespace grip::solver
