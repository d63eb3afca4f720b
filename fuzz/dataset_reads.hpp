#pragma once
// The reads `grip inspect` makes of a dataset (and its crash probe, app/dataset_probe.cpp):
// the layout, provenance, every object and gripper record, the summary (the candidate table
// and every committed row against its checksums) and a few trajectories and stress fields (of
// objects and fingers).
// Shared by the two dataset fuzz targets.
#include <cstdint>
#include <filesystem>

#include "io/dataset_reader.hpp"
#include "io/dataset_summary.hpp"

namespace grip::fuzz {

inline void read_like_inspect(const std::filesystem::path& file) {
  const io::DatasetReader reader(file);
  reader.job_id();
  reader.provenance();
  const io::DatasetLayout& layout = reader.layout();
  for (std::uint32_t o = 0; o < layout.objects.size(); ++o) reader.object(o);
  for (std::uint32_t g = 0; g < layout.grippers.size(); ++g) reader.gripper(g);
  io::summarize(reader);
  for (std::uint64_t id = 0; id < layout.candidate_count && id < 4; ++id) {
    reader.trajectory(id);
    reader.stress(id);
    reader.finger_stress(id);
  }
}

}  // namespace grip::fuzz
