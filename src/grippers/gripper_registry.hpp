#pragma once
// The gripper kinds grip knows, in one table: the name users type (--gripper, job files,
// candidate files), whether it is a parallel gripper or a hand, its joint count, how to build it,
// whether its fingers are meshed, and what one of its trials costs; and the soft parallel
// grippers users describe in files (src/grippers/gripper_description.hpp), typed as the file.
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "src/grippers/hand_model.hpp"
#include "src/grippers/leap_hand.hpp"
#include "src/grippers/parallel_gripper.hpp"

namespace grip::grippers {

// fin-ray: UMI-style soft fingers; parallel-jaw: rigid box fingers; leap: the 16-DoF hand;
// described: a soft parallel gripper from a description file.
enum class GripperKind { kFinRay, kParallelJaw, kLeap, kDescribed };

// One row of the table, or a described gripper. Exactly one of make_parallel and hand_files is
// set.
struct GripperType {
  GripperKind kind;
  std::string name;  // as typed (a description's [gripper] name); the dataset's gripper name
  int joints;        // joint values per hand: 1 (the opening, m) or the hand's DoFs (rad)
  // A parallel gripper's build; its fingers' tet mesh as the options say when meshed_finger.
  std::function<ParallelGripper(const FinRayOptions& finger)> make_parallel;
  LeapHandFiles (*hand_files)(HandSide);  // a hand's shipped URDF and points, per side
  // Soft fingers meshed with tets (grippers::FinRayOptions: grip trial --finger-layers).
  bool meshed_finger;
  // The least CPU time one trial of a rigid object takes, from `grip bench trial` on the 2-core
  // development machine (docs/results.md, "Trial cost"): what a job refused for its size is told
  // it would need at least. A described gripper's is the fin-ray's, scaled by its finger's tets.
  double trial_cpu_seconds;
  std::filesystem::path description;  // the file a described gripper was read from

  bool is_hand() const { return hand_files != nullptr; }
};

// Every kind, in the order names are listed.
std::span<const GripperType> gripper_types();
const GripperType& gripper_type(GripperKind kind);
// The row typed as `name`, or nullptr.
const GripperType* find_gripper_type(std::string_view name);
// The row typed as `name`; throws std::invalid_argument naming the known names.
const GripperType& gripper_type(std::string_view name);

// What a --gripper value or a job names: a built-in gripper by its name, or the gripper a
// description file (*.toml, gripper_description.hpp) describes. Throws std::invalid_argument
// naming the known names for an unknown name, config::ConfigError for a bad description.
GripperType resolve_gripper(const std::string& name_or_file);

// The names as typed, in table order.
std::vector<std::string> gripper_names();
// The same for people: "fin-ray, parallel-jaw or leap".
std::string gripper_name_list();

// The default build; throws std::invalid_argument when `kind` is a hand.
ParallelGripper make_parallel_gripper(GripperKind kind);
// Loads one side of a hand from its shipped files; throws std::invalid_argument when `kind` is
// a parallel gripper.
HandModel make_hand(GripperKind kind, HandSide side);

}  // namespace grip::grippers
