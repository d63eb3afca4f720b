#pragma once
// The shape of a dataset file: its group names (docs/dataset-format.md; its datasets are
// dataset_columns()) and every size derived from the plan, so that writer, resume and reader
// agree on where each candidate's bytes live.
#include <hdf5.h>

#include <cstdint>
#include <string>
#include <vector>

#include "io/dataset_plan.hpp"

namespace grip::io {

inline constexpr const char* kFormatName = "grip-dataset";
inline constexpr std::uint64_t kFormatVersion = 10;

struct DatasetLayout {
  std::uint64_t candidate_count = 0;
  std::uint32_t closing_frames = 0;
  std::uint32_t validation_frames = 0;
  // Widths of the per-hand table columns: the largest over all grippers (at least 1).
  std::uint32_t max_hands = 1;
  std::uint32_t max_joints = 1;
  std::uint32_t max_fingers = 1;

  struct Object {
    std::uint64_t vertices = 0;
    std::uint64_t tets = 0;
    std::uint64_t stress_slots = 0;
  };
  struct Gripper {
    std::uint32_t hands = 1;
    std::uint32_t joints = 0;
    std::uint32_t fingers = 0;
    std::uint64_t vertices = 0;  // per hand
    std::uint64_t tets = 0;      // of all hands' soft fingers (0: rigid fingers)
    std::uint64_t stress_slots = 0;
  };
  std::vector<Object> objects;
  std::vector<Gripper> grippers;

  // Per candidate: its object, gripper and slots (-1: none) in the trajectory datasets of
  // its (object, gripper) pair, in its object's stress dataset and in its gripper's.
  std::vector<std::uint32_t> object;
  std::vector<std::uint32_t> gripper;
  std::vector<std::int64_t> frame_slot;
  std::vector<std::int64_t> stress_slot;
  std::vector<std::int64_t> finger_stress_slot;
  // Trajectory slots per (object, gripper) pair, indexed object * grippers.size() + gripper.
  std::vector<std::uint64_t> trajectory_slots;

  std::uint32_t frames() const { return closing_frames + validation_frames; }
  std::size_t pair(std::uint32_t o, std::uint32_t g) const { return o * grippers.size() + g; }

  // Checks the plan (indices in range, stress only for soft tet objects and soft fingers, whole
  // vertices...)
  // and throws DatasetError naming the first problem.
  static DatasetLayout from_plan(const DatasetPlan& plan);
  // Reads the layout of an open dataset file; throws DatasetError when it is not one, when a
  // dataset's shape or a size attribute disagrees with the others, when a stored index lies
  // outside the sizes it indexes, or a plan column does not match its checksum.
  static DatasetLayout read(hid_t file);
};

std::string object_group(std::uint32_t object);    // "/objects/000012"
std::string gripper_group(std::uint32_t gripper);  // "/grippers/001"
std::string trajectory_group(std::uint32_t object, std::uint32_t gripper);
std::string stress_dataset(std::uint32_t object);
std::string finger_stress_dataset(std::uint32_t gripper);

}  // namespace grip::io
