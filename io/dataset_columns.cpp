#include "io/dataset_columns.hpp"

#include <algorithm>
#include <array>
#include <string_view>
#include <type_traits>
#include <variant>

#include "io/column_access.hpp"

namespace grip::io {

namespace {

using column_access::field;

// Extents: one value (a scalar dataset, or a row of one), a list, rows of kWidth values.
Dims one_value(const Sizes&) { return {}; }
Dims list(const Sizes& s) { return {s.count}; }
template <hsize_t kWidth>
Dims rows_of(const Sizes& s) {
  return {s.count / kWidth, kWidth};
}
// A stress slot's row: one value per object tet, or per tet of the gripper's soft fingers.
Dims per_tet(const Sizes& s) { return {s.object.tets}; }
Dims per_finger_tet(const Sizes& s) { return {s.gripper.tets}; }
// A frame slot's row, per frame: object and gripper vertex vectors, object pose, hand poses,
// joints.
Dims object_vectors(const Sizes& s) { return {s.frames, s.object.vertices, 3}; }
Dims gripper_vectors(const Sizes& s) { return {s.frames, s.gripper.hands * s.gripper.vertices, 3}; }
Dims object_pose(const Sizes& s) { return {s.frames, 3, 4}; }
Dims hand_poses(const Sizes& s) { return {s.frames, s.gripper.hands, 3, 4}; }
Dims hand_joints(const Sizes& s) { return {s.frames, s.gripper.hands, s.gripper.joints}; }
// A candidate's row; per-hand columns as wide as the largest gripper's.
Dims gravity_phases(const Sizes&) { return {6}; }
Dims table_hand_poses(const Sizes& s) { return {s.max_hands, 3, 4}; }
Dims table_joints(const Sizes& s) { return {s.max_hands, s.max_joints}; }
Dims table_fingers(const Sizes& s) { return {s.max_hands, s.max_fingers}; }
// A candidate's checksums: one per checksummed column.
Dims checksum_row(const Sizes&) { return {checksum_entries()}; }

// Values per hand of a gripper's candidate.
std::uint32_t pose_values(const DatasetLayout::Gripper&) { return 12; }
std::uint32_t joint_values(const DatasetLayout::Gripper& g) { return g.joints; }
std::uint32_t finger_values(const DatasetLayout::Gripper& g) { return g.fingers; }

// A candidate record's field.
template <auto... kMembers>
constexpr Access<CandidateResult> record_field() {
  return field<&CandidateResult::record, kMembers...>();
}

// 1 where the result has its optional part (trajectory or a stress); not read back.
template <auto kPart>
constexpr Access<CandidateResult> present() {
  return {column_access::values_holding<std::uint8_t>(),
          [](const CandidateResult& result, Values& out) {
            std::get<std::vector<std::uint8_t>>(out).push_back((result.*kPart) ? 1 : 0);
          },
          nullptr, [](const CandidateResult&) { return std::size_t{1}; }};
}

// The parameters as (key, value) rows.
constexpr Access<Provenance> parameter_pairs() {
  return {column_access::values_holding<std::string>(),
          [](const Provenance& provenance, Values& out) {
            auto& strings = std::get<std::vector<std::string>>(out);
            for (const Parameter& parameter : provenance.parameters) {
              strings.push_back(parameter.key);
              strings.push_back(parameter.value);
            }
          },
          [](const Values& in, Provenance& provenance) {
            const auto& strings = std::get<std::vector<std::string>>(in);
            provenance.parameters.clear();
            for (std::size_t i = 0; i + 1 < strings.size(); i += 2) {
              provenance.parameters.push_back({strings[i], strings[i + 1]});
            }
          },
          [](const Provenance& provenance) { return 2 * provenance.parameters.size(); }};
}

using P = Place;
using E = Element;
using F = Fill;

constexpr std::array kColumns = {
    // /provenance
    Column{"job_text", P::kProvenance, E::kString, F::kUnset, one_value,
           field<&Provenance::job_text>()},
    Column{"parameters", P::kProvenance, E::kString, F::kUnset, rows_of<2>, parameter_pairs()},
    // /objects/OOOOOO: rest meshes, then stress per stress slot
    Column{"vertices", P::kObject, E::kFloat64, F::kNever, rows_of<3>,
           field<&ObjectRecord::vertices>()},
    Column{"triangles", P::kObject, E::kInt32, F::kNever, rows_of<3>,
           field<&ObjectRecord::triangles>()},
    Column{"tets", P::kObject, E::kInt32, F::kNever, rows_of<4>, field<&ObjectRecord::tets>()},
    Column{"stress", P::kStress, E::kFloat32, F::kNever, per_tet,
           field<&CandidateResult::stress>()},
    // /objects/OOOOOO/trajectories/GGG: F frames per frame slot
    Column{"object_vertices", P::kTrajectory, E::kFloat32, F::kNever, object_vectors,
           field<&TrajectoryRecord::object_vertices>()},
    Column{"gripper_vertices", P::kTrajectory, E::kFloat32, F::kNever, gripper_vectors,
           field<&TrajectoryRecord::gripper_vertices>()},
    Column{"contact_forces", P::kTrajectory, E::kFloat32, F::kNever, object_vectors,
           field<&TrajectoryRecord::contact_forces>()},
    Column{"friction_forces", P::kTrajectory, E::kFloat32, F::kNever, object_vectors,
           field<&TrajectoryRecord::friction_forces>()},
    Column{"object_poses", P::kTrajectory, E::kFloat64, F::kNever, object_pose,
           field<&TrajectoryRecord::object_poses>()},
    Column{"hand_poses", P::kTrajectory, E::kFloat64, F::kNever, hand_poses,
           field<&TrajectoryRecord::hand_poses>()},
    Column{"joints", P::kTrajectory, E::kFloat64, F::kNever, hand_joints,
           field<&TrajectoryRecord::joints>()},
    Column{"gripper_contact_forces", P::kTrajectory, E::kFloat32, F::kNever, gripper_vectors,
           field<&TrajectoryRecord::gripper_contact_forces>()},
    Column{"gripper_friction_forces", P::kTrajectory, E::kFloat32, F::kNever, gripper_vectors,
           field<&TrajectoryRecord::gripper_friction_forces>()},
    // /grippers/GGG
    Column{"joint_names", P::kGripper, E::kString, F::kUnset, list,
           field<&GripperRecord::joint_names>()},
    Column{"finger_names", P::kGripper, E::kString, F::kUnset, list,
           field<&GripperRecord::finger_names>()},
    Column{"vertices", P::kGripper, E::kFloat64, F::kNever, rows_of<3>,
           field<&GripperRecord::vertices>()},
    Column{"triangles", P::kGripper, E::kInt32, F::kNever, rows_of<3>,
           field<&GripperRecord::triangles>()},
    Column{"tet_vertices", P::kGripper, E::kFloat64, F::kNever, rows_of<3>,
           field<&GripperRecord::tet_vertices>()},
    Column{"tets", P::kGripper, E::kInt32, F::kNever, rows_of<4>, field<&GripperRecord::tets>()},
    // /grippers/GGG: finger stress per finger stress slot
    Column{"finger_stress", P::kFingerStress, E::kFloat32, F::kNever, per_finger_tet,
           field<&CandidateResult::finger_stress>()},
    // /candidates: the plan's columns, the done flags, then the results'
    Column{"object", P::kPlan, E::kUint32, F::kNever, one_value, field<&DatasetLayout::object>()},
    Column{"gripper", P::kPlan, E::kUint32, F::kNever, one_value, field<&DatasetLayout::gripper>()},
    Column{"frame_slot", P::kPlan, E::kInt64, F::kNever, one_value,
           field<&DatasetLayout::frame_slot>()},
    Column{"stress_slot", P::kPlan, E::kInt64, F::kNever, one_value,
           field<&DatasetLayout::stress_slot>()},
    Column{"finger_stress_slot", P::kPlan, E::kInt64, F::kNever, one_value,
           field<&DatasetLayout::finger_stress_slot>()},
    Column{"done", P::kDone, E::kUint8, F::kZero, one_value, std::monostate{}},
    Column{"checksum", P::kChecksum, E::kUint32, F::kZero, checksum_row, std::monostate{}},
    Column{"status", P::kResult, E::kStatus, F::kZero, one_value,
           record_field<&CandidateRecord::status>()},
    Column{"failure", P::kResult, E::kFailureKind, F::kZero, one_value,
           record_field<&CandidateRecord::failure>()},
    Column{"hand_poses", P::kResult, E::kFloat64, F::kNaN, table_hand_poses,
           record_field<&CandidateRecord::hand_poses>(), pose_values},
    Column{"joints", P::kResult, E::kFloat64, F::kNaN, table_joints,
           record_field<&CandidateRecord::joints>(), joint_values},
    Column{"d1", P::kResult, E::kFloat64, F::kNaN, one_value, record_field<&CandidateRecord::d1>()},
    Column{"d2", P::kResult, E::kFloat64, F::kNaN, one_value, record_field<&CandidateRecord::d2>()},
    Column{"displacement", P::kResult, E::kFloat64, F::kNaN, gravity_phases,
           record_field<&CandidateRecord::displacement>()},
    Column{"phase_seconds", P::kResult, E::kFloat64, F::kNaN, gravity_phases,
           record_field<&CandidateRecord::phase_seconds>()},
    Column{"closing_forces", P::kResult, E::kFloat64, F::kNaN, table_fingers,
           record_field<&CandidateRecord::closing_forces>(), finger_values},
    Column{"contact_friction", P::kResult, E::kFloat64, F::kNaN, one_value,
           record_field<&CandidateRecord::contact_friction>()},
    Column{"newton_steps", P::kResult, E::kUint32, F::kZero, one_value,
           record_field<&CandidateRecord::newton, &NewtonStatistics::steps>()},
    Column{"newton_iterations", P::kResult, E::kUint32, F::kZero, one_value,
           record_field<&CandidateRecord::newton, &NewtonStatistics::iterations>()},
    Column{"newton_max_iterations", P::kResult, E::kUint32, F::kZero, one_value,
           record_field<&CandidateRecord::newton, &NewtonStatistics::max_iterations>()},
    Column{"newton_retries", P::kResult, E::kUint32, F::kZero, one_value,
           record_field<&CandidateRecord::newton, &NewtonStatistics::retries>()},
    Column{"simulated_frames", P::kResult, E::kUint32, F::kZero, one_value,
           record_field<&CandidateRecord::simulated_frames>()},
    Column{"wall_time", P::kResult, E::kFloat64, F::kNaN, one_value,
           record_field<&CandidateRecord::wall_time>()},
    Column{"trajectory_written", P::kResult, E::kUint8, F::kZero, one_value,
           present<&CandidateResult::trajectory>()},
    Column{"stress_written", P::kResult, E::kUint8, F::kZero, one_value,
           present<&CandidateResult::stress>()},
    Column{"finger_stress_written", P::kResult, E::kUint8, F::kZero, one_value,
           present<&CandidateResult::finger_stress>()},
};

// The record each place's columns are read from and written to (the Column::access alternative).
constexpr std::size_t access_index(Place place) {
  switch (place) {
    case Place::kProvenance:
      return 1;
    case Place::kObject:
      return 2;
    case Place::kGripper:
      return 3;
    case Place::kTrajectory:
      return 4;
    case Place::kPlan:
      return 5;
    case Place::kStress:
    case Place::kFingerStress:
    case Place::kResult:
      return 6;
    case Place::kDone:
    case Place::kChecksum:
      return 0;
  }
  return 0;
}

constexpr bool well_formed(const Column& column) {
  const std::size_t held = std::visit(
      [&](const auto& access) {
        if constexpr (std::is_same_v<std::remove_cvref_t<decltype(access)>, std::monostate>) {
          return value_index(column.element);
        } else {
          return access.value_index;
        }
      },
      column.access);
  return column.access.index() == access_index(column.place) &&
         held == value_index(column.element) &&
         (column.per_hand == nullptr || column.place == Place::kResult);
}

// Places sharing a group: a name may appear once per group.
constexpr int group_of(Place place) {
  switch (place) {
    case Place::kObject:
    case Place::kStress:
      return 1;
    case Place::kGripper:
    case Place::kFingerStress:
      return 3;
    case Place::kPlan:
    case Place::kResult:
    case Place::kDone:
    case Place::kChecksum:
      return 2;
    default:
      return 4 + static_cast<int>(place);
  }
}

constexpr bool names_unique_per_group() {
  for (std::size_t i = 0; i < kColumns.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (group_of(kColumns[i].place) == group_of(kColumns[j].place) &&
          std::string_view(kColumns[i].name) == kColumns[j].name) {
        return false;
      }
    }
  }
  return true;
}

static_assert(std::all_of(kColumns.begin(), kColumns.end(), well_formed),
              "a column's accessor must take its place's record and hold its element type; "
              "only candidate result columns have hands");
static_assert(names_unique_per_group(), "a column name appears twice in one group");

}  // namespace

std::span<const Column> dataset_columns() { return kColumns; }

bool checksummed(const Column& column) {
  return column.place == Place::kStress || column.place == Place::kFingerStress ||
         column.place == Place::kTrajectory || column.place == Place::kResult;
}

std::size_t checksum_entries() {
  return static_cast<std::size_t>(std::count_if(kColumns.begin(), kColumns.end(),
                                                [](const Column& c) { return checksummed(c); }));
}

std::size_t checksum_entry(const Column& column) {
  std::size_t entry = 0;
  for (const Column& c : kColumns) {
    if (&c == &column) return entry;
    entry += checksummed(c) ? 1 : 0;
  }
  return entry;
}

}  // namespace grip::io
