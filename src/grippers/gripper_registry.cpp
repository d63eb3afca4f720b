#include "src/grippers/gripper_registry.hpp"

#include <array>
#include <memory>
#include <stdexcept>

#include "src/grippers/gripper_description.hpp"

namespace grip::grippers {
namespace {

// Built on first use, so that lookups made while other files' statics are initialized find it.
const std::array<GripperType, 3>& table() {
  static const std::array<GripperType, 3> types{{
      {GripperKind::kFinRay,
       "fin-ray",
       1,
       [](const FinRayOptions& finger) { return make_umi_soft_gripper(finger); },
       nullptr,
       true,
       4.6,
       {}},
      {GripperKind::kParallelJaw,
       "parallel-jaw",
       1,
       [](const FinRayOptions&) { return make_rigid_jaw_gripper(); },
       nullptr,
       false,
       0.06,
       {}},
      {GripperKind::kLeap, "leap", 16, nullptr, shipped_leap_hand, false, 0.28, {}},
  }};
  return types;
}

GripperType described_gripper(const std::filesystem::path& file) {
  auto gripper = std::make_shared<const ParallelGripper>(load_gripper_description(file));
  // The production finger is meshed once per process, not per description read.
  static const double fin_ray_tets = static_cast<double>(make_fin_ray_finger().mesh.tets.rows());
  const double tets = static_cast<double>(gripper->soft_finger->mesh.tets.rows());
  const GripperType& fin_ray = gripper_type(GripperKind::kFinRay);
  return {GripperKind::kDescribed,
          gripper->name,
          1,
          [gripper](const FinRayOptions&) { return *gripper; },
          nullptr,
          false,
          fin_ray.trial_cpu_seconds * tets / fin_ray_tets,
          file};
}

}  // namespace

std::span<const GripperType> gripper_types() { return table(); }

const GripperType& gripper_type(GripperKind kind) {
  for (const GripperType& type : table()) {
    if (type.kind == kind) return type;
  }
  // A described gripper has no row: it is what resolve_gripper read from its file.
  throw std::invalid_argument("gripper_type: no built-in gripper of this kind");
}

const GripperType* find_gripper_type(std::string_view name) {
  for (const GripperType& type : table()) {
    if (type.name == name) return &type;
  }
  return nullptr;
}

const GripperType& gripper_type(std::string_view name) {
  if (const GripperType* type = find_gripper_type(name)) return *type;
  throw std::invalid_argument("unknown gripper '" + std::string(name) +
                              "' (known: " + gripper_name_list() + ")");
}

GripperType resolve_gripper(const std::string& name_or_file) {
  if (const GripperType* type = find_gripper_type(name_or_file)) return *type;
  if (is_gripper_description(name_or_file)) return described_gripper(name_or_file);
  throw std::invalid_argument("unknown gripper '" + name_or_file + "' (known: " +
                              gripper_name_list() + ", or a gripper description file *.toml)");
}

std::vector<std::string> gripper_names() {
  std::vector<std::string> names;
  for (const GripperType& type : table()) names.emplace_back(type.name);
  return names;
}

std::string gripper_name_list() {
  std::string list;
  for (std::size_t i = 0; i < table().size(); ++i) {
    if (i > 0) list += i + 1 < table().size() ? ", " : " or ";
    list += table()[i].name;
  }
  return list;
}

ParallelGripper make_parallel_gripper(GripperKind kind) {
  const GripperType& type = gripper_type(kind);
  if (!type.make_parallel) {
    throw std::invalid_argument("the " + type.name + " hand is not a parallel gripper");
  }
  return type.make_parallel(FinRayOptions{});
}

HandModel make_hand(GripperKind kind, HandSide side) {
  const GripperType& type = gripper_type(kind);
  if (!type.hand_files) {
    throw std::invalid_argument("the " + type.name + " gripper is a parallel gripper, not a hand");
  }
  const LeapHandFiles files = type.hand_files(side);
  return load_hand_model(files.urdf, files.points);
}

}  // namespace grip::grippers
