#include "src/synth/candidate.hpp"

namespace grip::synth {

std::vector<double> pose_row_major(const Eigen::Isometry3d& pose) {
  std::vector<double> values(12);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) values[static_cast<std::size_t>(4 * r + c)] = pose.linear()(r, c);
    values[static_cast<std::size_t>(4 * r + 3)] = pose.translation()(r);
  }
  return values;
}

}  // namespace grip::synth
