#pragma once
// Writes committed results into the rows planned for them by hyperslab: the candidate table's
// result, checksum and done columns, the trajectory and stress rows of each object, either
// collectively (every rank joins each write) or by this rank alone.
#include <hdf5.h>

#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "io/candidate_record.hpp"
#include "io/dataset_layout.hpp"
#include "io/hdf5.hpp"

namespace grip::io {

// Results in id order: a union of row hyperslabs is written in row order.
std::vector<const CandidateResult*> sorted_by_id(std::span<const CandidateResult> results);
std::vector<std::uint64_t> ids_of(const std::vector<const CandidateResult*>& sorted);
// The per-object and per-gripper datasets the results write into, as flags: trajectories per
// (object, gripper) pair, then stress per object, then finger stress per gripper. In a
// collective write every rank joins any rank's.
std::vector<std::uint8_t> touched_by(const DatasetLayout& layout,
                                     const std::vector<const CandidateResult*>& sorted);

class RowWriter {
 public:
  RowWriter() = default;
  // Collective: opens every dataset rows are written into in `file` (named `name` in errors),
  // every rank together, so that a rank's independent writes touch raw data only, no metadata.
  RowWriter(hid_t file, const DatasetLayout& layout, std::string name);

  // Writes `sorted`'s rows and checksums into every row dataset in `touched` (candidate table,
  // then trajectories per pair, stress per object, finger stress per gripper): collectively,
  // every rank joining each, or independently, one write per run of consecutive rows.
  void write_results(const DatasetLayout& layout, const std::vector<const CandidateResult*>& sorted,
                     const std::vector<std::uint8_t>& touched, bool collective) const;
  // Sets the done flags of `rows` (ascending).
  void write_done(const std::vector<std::uint64_t>& rows, bool collective) const;

 private:
  struct ResultRows;

  hid_t dataset(const std::string& path) const;

  std::string name_;
  std::map<std::string, h5::Handle> datasets_;  // by path
  h5::Handle collective_;                       // collective MPI-IO data transfer
  h5::Handle independent_;                      // independent MPI-IO data transfer
};

}  // namespace grip::io
