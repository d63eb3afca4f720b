#pragma once
// Writes a dataset collectively over an MPI communicator with parallel HDF5: create() lays out
// the whole file from the plan at once (fixed sizes, contiguous, space allocated up front), so
// later writes touch raw data at fixed offsets only; write() commits a batch of results from
// every rank (rows and their checksums, flush, done flags, flush, fsync'd journal line);
// resume() reopens a file of the same job and reports which candidates are already done.
#include <mpi.h>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <vector>

#include "io/candidate_record.hpp"
#include "io/dataset_damage.hpp"
#include "io/dataset_layout.hpp"
#include "io/dataset_plan.hpp"
#include "io/hdf5.hpp"
#include "io/journal.hpp"
#include "io/provenance.hpp"

namespace grip::io {

class DatasetWriter {
 public:
  // Collective. Creates `path` and its journal; refuses (DatasetError, nothing written) if
  // either exists or the plan is inconsistent. Every rank passes the same plan and provenance.
  static DatasetWriter create(const std::filesystem::path& path, const DatasetPlan& plan,
                              const Provenance& provenance, MPI_Comm comm);
  // Collective. Reopens a dataset made by the same job (same job text and seed). Refuses with
  // a DatasetError, leaving the file and journal byte for byte untouched, when the file is not
  // an HDF5 file, is truncated, is not a grip dataset, belongs to another job, holds an index
  // outside the sizes it indexes or a plan column that does not match its checksum. Committed
  // rows that do not match their checksums are pending again (damaged() lists them).
  static DatasetWriter resume(const std::filesystem::path& path, const Provenance& provenance,
                              MPI_Comm comm);

  DatasetWriter(DatasetWriter&&) noexcept;
  DatasetWriter& operator=(DatasetWriter&&) noexcept;
  ~DatasetWriter();  // closes the file (collective: every rank destroys its writer)

  const DatasetLayout& layout() const { return layout_; }
  // Committed candidates: both their file flag and a journal line say so. Same on every rank.
  bool is_done(std::uint64_t id) const { return done_[id] != 0; }
  std::vector<std::uint64_t> pending() const;
  // On rank 0 after resume(): the committed rows found damaged, now pending. Empty elsewhere.
  const std::vector<Damage>& damaged() const { return damaged_; }

  // Collective: every rank calls it, the same number of times, each with its own results
  // (possibly none); the batch is committed when it returns. Each result's id
  // must be pending and appear once over all ranks; its sizes must match its gripper and
  // object. On bad input every rank throws the same DatasetError and nothing is written.
  void write(std::span<const CandidateResult> results);

  // Collective: closes the file. Called by the destructor if not called before.
  void close();

 private:
  DatasetWriter(std::filesystem::path path, DatasetLayout layout, MPI_Comm comm);
  void open_collective(bool create);

  std::filesystem::path path_;
  DatasetLayout layout_;
  MPI_Comm comm_ = MPI_COMM_NULL;
  int rank_ = 0;
  h5::Handle file_;
  h5::Handle transfer_;  // collective MPI-IO data transfer
  std::vector<std::uint8_t> done_;
  std::vector<Damage> damaged_;
  std::optional<Journal> journal_;  // rank 0 only
};

}  // namespace grip::io
