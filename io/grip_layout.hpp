#pragma once
// GRIP's released layout (the GRIP_Dataset repository): one HDF5 file per gripper and object,
// `<gripper>_<object>_<soft|rigid>.h5`, with `object_config/` (the object's material) and
// `trajectories/` (every kept grasp's frames, stacked along a leading pose axis), so that code
// written for GRIP's data reads grip's. docs/dataset-format.md, "GRIP's layout", maps every key
// to grip's own.
#include <filesystem>
#include <string>
#include <vector>

#include "io/dataset_reader.hpp"

namespace grip::io {

struct GripLayoutOptions {
  // GRIP keeps only the grasps that held; `all` keeps every committed candidate with a
  // trajectory, its verdict in `trajectories/success` and `trajectories/failure`.
  bool all = false;
};

struct GripLayoutFile {
  std::filesystem::path path;
  std::uint64_t poses = 0;
};

// Writes one file per (gripper, object) pair with at least one grasp to keep, into `folder`
// (created if missing). Throws DatasetError, before writing anything, when a file it would
// write exists already; each file is written under a temporary name and renamed when complete.
std::vector<GripLayoutFile> export_grip_layout(const DatasetReader& dataset,
                                               const std::filesystem::path& folder,
                                               const GripLayoutOptions& options);

}  // namespace grip::io
