#pragma once
// Everything a dataset's structure depends on, known before any trial runs: objects,
// grippers and one slot per candidate. The writer lays the whole file out from it at once.
#include <cstdint>
#include <vector>

#include "io/gripper_record.hpp"
#include "io/object_record.hpp"

namespace grip::io {

struct CandidateSlot {
  std::uint32_t object = 0;    // index into DatasetPlan::objects
  std::uint32_t gripper = 0;   // index into DatasetPlan::grippers
  bool frames = false;         // store this candidate's trajectory
  bool stress = false;         // store its object's stress (soft objects only)
  bool finger_stress = false;  // store its fingers' stress (soft fingers only)
};

struct DatasetPlan {
  std::vector<ObjectRecord> objects;
  std::vector<GripperRecord> grippers;
  std::vector<CandidateSlot> candidates;  // candidate id = index
  std::uint32_t closing_frames = 40;      // GRIP's released files: 40 closing +
  std::uint32_t validation_frames = 60;   // 60 validation (10 per gravity axis)
};

}  // namespace grip::io
