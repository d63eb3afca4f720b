#include "bench/scale/commit_fit.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace grip::bench {
namespace {

// Least squares over the terms switched on in `use` (latency, log2 ranks, bytes); the
// coefficients of the others are 0. False when the normal equations are singular.
bool least_squares(const std::vector<CommitPoint>& points, const std::array<bool, 3>& use,
                   std::array<double, 3>& coefficients) {
  std::array<std::array<double, 4>, 3> a{};  // normal equations, augmented
  for (const CommitPoint& p : points) {
    const std::array<double, 3> x = {1.0, std::log2(static_cast<double>(p.ranks)), p.bytes};
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) a[i][j] += use[i] && use[j] ? x[i] * x[j] : 0.0;
      a[i][3] += use[i] ? x[i] * p.seconds : 0.0;
    }
  }
  for (int i = 0; i < 3; ++i) {
    if (!use[i]) a[i][i] = 1.0;  // that coefficient solves to 0
  }
  for (int c = 0; c < 3; ++c) {  // Gauss-Jordan with partial pivoting
    int pivot = c;
    for (int r = c + 1; r < 3; ++r) {
      if (std::abs(a[r][c]) > std::abs(a[pivot][c])) pivot = r;
    }
    if (std::abs(a[pivot][c]) < 1e-300) return false;
    std::swap(a[c], a[pivot]);
    for (int r = 0; r < 3; ++r) {
      if (r == c) continue;
      const double f = a[r][c] / a[c][c];
      for (int k = c; k < 4; ++k) a[r][k] -= f * a[c][k];
    }
  }
  for (int i = 0; i < 3; ++i) coefficients[i] = a[i][3] / a[i][i];
  return true;
}

}  // namespace

CommitModel fit_commit_model(const std::vector<CommitPoint>& points) {
  std::array<bool, 3> use = {true, true, true};
  std::array<double, 3> c{};
  for (;;) {  // each pass drops a term, so at most three
    const bool solved = least_squares(points, use, c);
    bool dropped = false;
    for (int i = 2; i >= 1; --i) {
      if (use[i] && (!solved || c[i] < 0) && !dropped) use[i] = false, dropped = true;
    }
    if (solved && !dropped) break;
    if (!dropped) return {};  // no points
  }
  CommitModel model;
  model.latency = std::max(0.0, c[0]);
  model.per_log2 = c[1];
  model.bandwidth = c[2] > 0 ? 1.0 / c[2] : 0.0;
  return model;
}

CommitModel fit_unit_commit_model(const std::vector<CommitPoint>& points) {
  std::vector<CommitPoint> flat = points;
  for (CommitPoint& p : flat) p.ranks = 1;  // log2(1) = 0: that term drops out
  std::array<double, 3> c{};
  CommitModel model;
  if (least_squares(flat, {true, false, true}, c) && c[2] > 0) {
    model.latency = std::max(0.0, c[0]);
    model.bandwidth = 1.0 / c[2];
  } else if (least_squares(flat, {true, false, false}, c)) {
    model.latency = std::max(0.0, c[0]);
  }
  return model;
}

}  // namespace grip::bench
