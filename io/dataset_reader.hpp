#pragma once
// Reads a grip dataset back (serial HDF5, no MPI needed): provenance, objects, grippers, the
// candidate table and, per candidate, its trajectory and stresses where they were written.
// Used by `grip inspect`, tests and any C++ consumer; Python readers use h5py directly
// (examples/read_dataset.py).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/candidate_record.hpp"
#include "io/dataset_damage.hpp"
#include "io/dataset_layout.hpp"
#include "io/gripper_record.hpp"
#include "io/hdf5.hpp"
#include "io/object_record.hpp"
#include "io/provenance.hpp"

namespace grip::io {

class DatasetReader {
 public:
  // Opens read-only. Throws DatasetError naming the file when it is missing, not HDF5,
  // truncated, not a grip dataset or of another format version, when a stored index lies
  // outside the sizes it indexes, or a plan column does not match its checksum.
  explicit DatasetReader(const std::filesystem::path& path);

  const std::filesystem::path& path() const { return path_; }
  const DatasetLayout& layout() const { return layout_; }
  std::string job_id() const;
  // These three check what they read against the checksums written at creation.
  Provenance provenance() const;
  ObjectRecord object(std::uint32_t index) const;
  GripperRecord gripper(std::uint32_t index) const;

  std::vector<std::uint8_t> done() const;  // 1 where the candidate's done flag is set
  // The rows of done candidates that do not match the checksums written with them: such a
  // candidate is not done. Reads every committed row (as long as reading the file).
  std::vector<Damage> damage() const;
  // Every row of the candidate table, unpadded to each gripper's sizes; rows not written yet
  // have status kPending.
  std::vector<CandidateRecord> candidates() const;
  // The candidate's trajectory or stress, or nothing where none was committed.
  std::optional<TrajectoryRecord> trajectory(std::uint64_t id) const;
  // Whether trajectory(id) holds one, without reading it.
  bool has_trajectory(std::uint64_t id) const;
  std::optional<std::vector<float>> stress(std::uint64_t id) const;
  // Von Mises stress per tet of the soft fingers (GripperRecord::tets), settled grasp.
  std::optional<std::vector<float>> finger_stress(std::uint64_t id) const;

 private:
  bool committed(std::uint64_t id, const char* written_column) const;

  std::filesystem::path path_;
  h5::Handle file_;
  DatasetLayout layout_;
};

}  // namespace grip::io
