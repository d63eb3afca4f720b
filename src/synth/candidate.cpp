#include "src/synth/candidate.hpp"

#include <stdexcept>
#include <string>

namespace grip::synth {

std::string_view gripper_name(GripperKind kind) {
  switch (kind) {
    case GripperKind::kFinRay: return "fin-ray";
    case GripperKind::kParallelJaw: return "parallel-jaw";
    case GripperKind::kLeap: return "leap";
  }
  throw std::invalid_argument("unknown gripper kind");
}

GripperKind parse_gripper_kind(std::string_view name) {
  for (const GripperKind kind : {GripperKind::kFinRay, GripperKind::kParallelJaw, GripperKind::kLeap}) {
    if (gripper_name(kind) == name) return kind;
  }
  throw std::invalid_argument("unknown gripper '" + std::string(name) +
                              "' (known: fin-ray, parallel-jaw, leap)");
}

int joints_per_hand(GripperKind kind) { return kind == GripperKind::kLeap ? 16 : 1; }

std::vector<double> pose_row_major(const Eigen::Isometry3d& pose) {
  std::vector<double> values(12);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) values[static_cast<std::size_t>(4 * r + c)] = pose.linear()(r, c);
    values[static_cast<std::size_t>(4 * r + 3)] = pose.translation()(r);
  }
  return values;
}

}  // namespace grip::synth
