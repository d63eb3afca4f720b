#include "src/grippers/gripper_registry.hpp"

#include <array>
#include <stdexcept>

namespace grip::grippers {
namespace {

constexpr std::array<GripperType, 3> kGripperTypes{{
    {GripperKind::kFinRay, "fin-ray", 1,
     [](const FinRayOptions& finger) { return make_umi_soft_gripper(finger); }, nullptr, true,
     17.0},
    {GripperKind::kParallelJaw, "parallel-jaw", 1,
     [](const FinRayOptions&) { return make_rigid_jaw_gripper(); }, nullptr, false, 0.06},
    {GripperKind::kLeap, "leap", 16, nullptr, shipped_leap_hand, false, 0.28},
}};

}  // namespace

std::span<const GripperType> gripper_types() { return kGripperTypes; }

const GripperType& gripper_type(GripperKind kind) {
  for (const GripperType& type : kGripperTypes) {
    if (type.kind == kind) return type;
  }
  throw std::invalid_argument("unknown gripper kind");
}

const GripperType* find_gripper_type(std::string_view name) {
  for (const GripperType& type : kGripperTypes) {
    if (type.name == name) return &type;
  }
  return nullptr;
}

const GripperType& gripper_type(std::string_view name) {
  if (const GripperType* type = find_gripper_type(name)) return *type;
  throw std::invalid_argument("unknown gripper '" + std::string(name) +
                              "' (known: " + gripper_name_list() + ")");
}

std::vector<std::string> gripper_names() {
  std::vector<std::string> names;
  for (const GripperType& type : kGripperTypes) names.emplace_back(type.name);
  return names;
}

std::string gripper_name_list() {
  std::string list;
  for (std::size_t i = 0; i < kGripperTypes.size(); ++i) {
    if (i > 0) list += i + 1 < kGripperTypes.size() ? ", " : " or ";
    list += kGripperTypes[i].name;
  }
  return list;
}

ParallelGripper make_parallel_gripper(GripperKind kind) {
  const GripperType& type = gripper_type(kind);
  if (!type.make_parallel) {
    throw std::invalid_argument("the " + std::string(type.name) +
                                " hand is not a parallel gripper");
  }
  return type.make_parallel(FinRayOptions{});
}

HandModel make_hand(GripperKind kind, HandSide side) {
  const GripperType& type = gripper_type(kind);
  if (!type.hand_files) {
    throw std::invalid_argument("the " + std::string(type.name) +
                                " gripper is a parallel gripper, not a hand");
  }
  const LeapHandFiles files = type.hand_files(side);
  return load_hand_model(files.urdf, files.points);
}

}  // namespace grip::grippers
