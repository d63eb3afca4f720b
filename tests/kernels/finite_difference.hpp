#pragma once
// Central finite differences over fixed-size Eigen vectors and a relative-error comparison,
// for checking analytic gradients, Jacobians and Hessians of the per-primitive kernels.

#include <gtest/gtest.h>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace grip::test {

// Central-difference gradient of a scalar function f: R^N -> R, step h per coordinate
// (truncation error O(h^2 f''')).
template <int N, typename F>
Eigen::Matrix<double, N, 1> fd_gradient(const Eigen::Matrix<double, N, 1>& x, F&& f, double h) {
  Eigen::Matrix<double, N, 1> g;
  for (int i = 0; i < N; ++i) {
    Eigen::Matrix<double, N, 1> xp = x, xm = x;
    xp[i] += h;
    xm[i] -= h;
    g[i] = (f(xp) - f(xm)) / (2.0 * h);
  }
  return g;
}

// Central-difference Jacobian of a vector function f: R^N -> R^M (column j is df/dx_j).
// The Hessian of a scalar energy is the Jacobian of its analytic gradient.
template <int M, int N, typename F>
Eigen::Matrix<double, M, N> fd_jacobian(const Eigen::Matrix<double, N, 1>& x, F&& f, double h) {
  Eigen::Matrix<double, M, N> jac;
  for (int j = 0; j < N; ++j) {
    Eigen::Matrix<double, N, 1> xp = x, xm = x;
    xp[j] += h;
    xm[j] -= h;
    const Eigen::Matrix<double, M, 1> fp = f(xp);
    const Eigen::Matrix<double, M, 1> fm = f(xm);
    jac.col(j) = (fp - fm) / (2.0 * h);
  }
  return jac;
}

// ||a - b|| / max(||a||, ||b||, floor) in the Frobenius norm. The floor is the magnitude below
// which differences count as absolute (round-off of a quantity that should be ~0).
template <typename A, typename B>
double relative_error(const Eigen::MatrixBase<A>& a, const Eigen::MatrixBase<B>& b, double floor) {
  const double scale = std::max({a.norm(), b.norm(), floor});
  return (a - b).norm() / scale;
}

// GoogleTest predicate: EXPECT_TRUE(relatively_close(analytic, numeric, 1e-6, floor)).
// On failure it prints both matrices and the error, so a failing random case can be replayed.
template <typename A, typename B>
::testing::AssertionResult relatively_close(const Eigen::MatrixBase<A>& actual,
                                            const Eigen::MatrixBase<B>& expected, double tolerance,
                                            double floor) {
  const double err = relative_error(actual, expected, floor);
  if (err <= tolerance) return ::testing::AssertionSuccess();
  std::ostringstream out;
  out.precision(17);
  out << "relative error " << err << " > " << tolerance << " (floor " << floor << ")\nactual:\n"
      << actual << "\nexpected:\n"
      << expected;
  return ::testing::AssertionFailure() << out.str();
}

// Smallest relative error of an analytic gradient against central differences over the ladder of
// steps h = scale * 10^-k, k = 1..12. Truncation error shrinks and round-off grows as h
// shrinks, and which step balances them depends on the configuration's scale (a distance of 1e-9
// wants a different step than one of 1): a correct derivative matches at some rung of the ladder,
// a wrong one at none.
template <int N, typename F, typename A>
double min_fd_gradient_error(const Eigen::Matrix<double, N, 1>& x, F&& f,
                             const Eigen::MatrixBase<A>& analytic, double scale, double floor) {
  double best = std::numeric_limits<double>::infinity();
  for (int k = 1; k <= 12; ++k)
    best = std::min(
        best, relative_error(analytic, fd_gradient<N>(x, f, scale * std::pow(10.0, -k)), floor));
  return best;
}

// The same for a Jacobian (a Hessian when f is the analytic gradient).
template <int M, int N, typename F, typename A>
double min_fd_jacobian_error(const Eigen::Matrix<double, N, 1>& x, F&& f,
                             const Eigen::MatrixBase<A>& analytic, double scale, double floor) {
  double best = std::numeric_limits<double>::infinity();
  for (int k = 1; k <= 12; ++k)
    best = std::min(
        best, relative_error(analytic, fd_jacobian<M, N>(x, f, scale * std::pow(10.0, -k)), floor));
  return best;
}

}  // namespace grip::test
