#pragma once
// k-means clustering of 3-D points (k-means++ seeding, then Lloyd iterations), deterministic
// for a seed; bimanual composition groups hand candidates by their contact centres with it.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace grip::synth {

using Points3 = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

struct Clustering {
  Points3 centres;          // k rows (k = min(k, number of points))
  std::vector<int> labels;  // cluster of each point
};

// Throws std::invalid_argument for k < 1 or no points.
Clustering kmeans(const Points3& points, int k, std::uint64_t seed, int max_iterations = 100);

}  // namespace grip::synth
