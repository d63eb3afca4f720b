#include "src/synth/kmeans.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "src/synth/candidate_random.hpp"

namespace grip::synth {

Clustering kmeans(const Points3& points, int k, std::uint64_t seed, int max_iterations) {
  const int n = static_cast<int>(points.rows());
  if (k < 1 || n == 0) throw std::invalid_argument("kmeans: needs k >= 1 and at least one point");
  k = std::min(k, n);
  CandidateRandom random(seed, 31, 0);
  Clustering result;
  result.centres.resize(k, 3);
  // k-means++: each next centre drawn with probability proportional to squared distance.
  result.centres.row(0) = points.row(random.below(n));
  Eigen::VectorXd nearest = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::infinity());
  for (int c = 1; c < k; ++c) {
    for (int i = 0; i < n; ++i) {
      nearest(i) = std::min(nearest(i), (points.row(i) - result.centres.row(c - 1)).squaredNorm());
    }
    const double total = nearest.sum();
    int chosen = n - 1;
    if (total > 0.0) {
      double target = random.uniform() * total;
      for (int i = 0; i < n; ++i) {
        target -= nearest(i);
        if (target < 0.0) {
          chosen = i;
          break;
        }
      }
    } else {
      chosen = random.below(n);
    }
    result.centres.row(c) = points.row(chosen);
  }
  result.labels.assign(static_cast<std::size_t>(n), -1);
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    bool changed = false;
    for (int i = 0; i < n; ++i) {
      int best = 0;
      (result.centres.rowwise() - points.row(i)).rowwise().squaredNorm().minCoeff(&best);
      if (result.labels[static_cast<std::size_t>(i)] != best) {
        result.labels[static_cast<std::size_t>(i)] = best;
        changed = true;
      }
    }
    if (!changed) break;
    Points3 sums = Points3::Zero(k, 3);
    Eigen::VectorXi sizes = Eigen::VectorXi::Zero(k);
    for (int i = 0; i < n; ++i) {
      sums.row(result.labels[static_cast<std::size_t>(i)]) += points.row(i);
      ++sizes(result.labels[static_cast<std::size_t>(i)]);
    }
    for (int c = 0; c < k; ++c) {
      if (sizes(c) > 0) result.centres.row(c) = sums.row(c) / sizes(c);  // an empty one stays put
    }
  }
  return result;
}

}  // namespace grip::synth
