#pragma once
// Writes a dataset over an MPI communicator with parallel HDF5: create() lays out the whole
// file from the plan at once (fixed sizes, contiguous, space allocated up front), so later writes
// touch raw data at fixed offsets only; commit_unit() commits one rank's work unit alone
// (independent writes, a sync, its ids to rank 0's journal), write() a batch from every rank
// collectively; resume() reopens a file of the same job and reports which candidates are done.
// Each concern is its own file: layout_writer, row_writer, result_check, sync_file,
// journal_relay, resume_state.
#include <mpi.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <span>
#include <vector>

#include "io/candidate_record.hpp"
#include "io/dataset_damage.hpp"
#include "io/dataset_layout.hpp"
#include "io/dataset_plan.hpp"
#include "io/hdf5.hpp"
#include "io/journal_relay.hpp"
#include "io/provenance.hpp"
#include "io/row_writer.hpp"
#include "io/sync_file.hpp"

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
  // Collective, after resume(): throws the same DatasetError on every rank, changing nothing,
  // when `plan` (the job planned again) has other objects, grippers or candidate slots than
  // the dataset was created with. Same job text and seed promise the same plan only from the
  // same grip; this holds a resumed run to it.
  void check_plan(const DatasetPlan& plan) const;

  DatasetWriter(DatasetWriter&&) noexcept;
  DatasetWriter& operator=(DatasetWriter&&) noexcept;
  ~DatasetWriter();  // closes the file (collective: every rank destroys its writer)

  const DatasetLayout& layout() const { return layout_; }
  // Committed candidates: both their file flag and a journal line say so. Same on every rank
  // after create() and resume() and after each write(); commit_unit() adds this rank's only.
  bool is_done(std::uint64_t id) const { return done_[id] != 0; }
  std::vector<std::uint64_t> pending() const;
  // On rank 0 after resume(): the committed rows found damaged, now pending. Empty elsewhere.
  const std::vector<Damage>& damaged() const { return damaged_; }

  // Collective: every rank calls it, the same number of times, each with its own results
  // (possibly none); the batch is committed when it returns. Each result's id
  // must be pending and appear once over all ranks; its sizes must match its gripper and
  // object. On bad input every rank throws the same DatasetError and nothing is written.
  void write(std::span<const CandidateResult> results);

  // Independent: this rank alone commits one work unit's results, no other rank taking part:
  // rows, checksums and done flags by independent MPI-IO writes at their planned places, synced
  // to disk, then the ids go to the journal (rank 0 appends its own at once, other ranks' at its
  // poll_journal()). Each id must be pending and given to one rank only (the caller's claims
  // guarantee it); a bad result throws DatasetError on this rank and nothing is written.
  void commit_unit(std::span<const CandidateResult> results);
  // Returns at once. Rank 0: appends the ids other ranks have sent to the journal (one fsync'd
  // line). Other ranks: releases the sends rank 0 has received.
  void poll_journal();
  // Collective: returns once every rank's commit_unit() calls are in the journal, rank 0
  // calling `while_waiting` and polling the journal as it waits for the others.
  void end_units(const std::function<void()>& while_waiting);

  // Collective: closes the file. Called by the destructor if not called before.
  void close();

 private:
  DatasetWriter(std::filesystem::path path, MPI_Comm comm);
  void open_collective(bool create);
  void check_open() const;

  std::filesystem::path path_;
  DatasetLayout layout_;
  MPI_Comm comm_ = MPI_COMM_NULL;
  int rank_ = 0;
  h5::Handle file_;
  SyncFile sync_file_;
  RowWriter row_writer_;  // opened once the layout is in the file
  std::vector<std::uint8_t> done_;
  std::vector<Damage> damaged_;
  JournalRelay journal_;
};

}  // namespace grip::io
