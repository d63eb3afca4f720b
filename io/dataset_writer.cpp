#include "io/dataset_writer.hpp"

#include <algorithm>
#include <numeric>
#include <string>
#include <utility>

#include "io/agree.hpp"
#include "io/dataset_error.hpp"
#include "io/layout_writer.hpp"
#include "io/result_check.hpp"
#include "io/resume_state.hpp"

namespace grip::io {

namespace {

// The ids of every rank's results, sorted (collective).
std::vector<std::uint64_t> gathered_ids(std::span<const CandidateResult> results, MPI_Comm comm) {
  std::vector<std::uint64_t> mine;
  for (const CandidateResult& result : results) mine.push_back(result.record.id);
  int size = 0;
  MPI_Comm_size(comm, &size);
  const int my_count = static_cast<int>(mine.size());
  std::vector<int> counts(static_cast<std::size_t>(size));
  MPI_Allgather(&my_count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  std::vector<int> offsets(counts.size(), 0);
  std::partial_sum(counts.begin(), counts.end() - 1, offsets.begin() + 1);
  std::vector<std::uint64_t> all(static_cast<std::size_t>(offsets.back() + counts.back()));
  MPI_Allgatherv(mine.data(), my_count, MPI_UINT64_T, all.data(), counts.data(), offsets.data(),
                 MPI_UINT64_T, comm);
  std::sort(all.begin(), all.end());
  return all;
}

}  // namespace

DatasetWriter::DatasetWriter(std::filesystem::path path, MPI_Comm comm)
    : path_(std::move(path)), comm_(comm), journal_(comm) {
  MPI_Comm_rank(comm, &rank_);
}

DatasetWriter::DatasetWriter(DatasetWriter&&) noexcept = default;
DatasetWriter& DatasetWriter::operator=(DatasetWriter&&) noexcept = default;

DatasetWriter::~DatasetWriter() { close(); }

void DatasetWriter::close() {
  row_writer_ = RowWriter();
  file_.reset();
  sync_file_ = SyncFile();
  journal_.close();
}

void DatasetWriter::open_collective(bool create) {
  const h5::Handle access =
      h5::plist_handle(H5Pcreate(H5P_FILE_ACCESS), "creating file access properties");
  h5::check(H5Pset_fapl_mpio(access, comm_, MPI_INFO_NULL), "choosing MPI-IO");
  const std::string name = path_.string();
  file_ = create ? h5::file_handle(H5Fcreate(name.c_str(), H5F_ACC_EXCL, H5P_DEFAULT, access),
                                   name + ": cannot create the dataset")
                 : h5::file_handle(H5Fopen(name.c_str(), H5F_ACC_RDWR, access),
                                   name + ": cannot open the dataset for writing");
  sync_file_ = SyncFile(path_);
}

void DatasetWriter::check_open() const {
  if (file_.get() < 0) throw DatasetError(path_.string() + ": the writer is closed");
}

DatasetWriter DatasetWriter::create(const std::filesystem::path& path, const DatasetPlan& plan,
                                    const Provenance& provenance, MPI_Comm comm) {
  h5::silence_errors();
  DatasetWriter writer(path, comm);
  agree(comm, [&] { writer.layout_ = DatasetLayout::from_plan(plan); });
  const std::filesystem::path journal = Journal::path_for(path);
  agree(comm, [&] {
    if (writer.rank_ != 0) return;
    if (std::filesystem::exists(path)) {
      throw DatasetError(path.string() +
                         ": the dataset already exists; resume it (--resume) "
                         "or choose another output file");
    }
    if (std::filesystem::exists(journal)) {
      throw DatasetError(journal.string() +
                         ": a journal without its dataset exists; remove "
                         "it or choose another output file");
    }
  });
  agree(comm, [&] {  // H5Fcreate fails alike on every rank (e.g. a missing folder)
    writer.open_collective(true);
  });
  write_layout(writer.file_, plan, writer.layout_, provenance, writer.rank_);
  h5::check(H5Fflush(writer.file_, H5F_SCOPE_GLOBAL), path.string() + ": flushing the layout");
  // The journal's existence says the layout is complete: a crash before this line leaves a
  // dataset that resume() refuses, never one that looks resumable but is half made.
  agree(comm, [&] {
    if (writer.rank_ == 0) {
      writer.journal_.open(Journal::create(journal, job_id(provenance.job_text, provenance.seed),
                                           writer.layout_.candidate_count));
    }
  });
  writer.done_.assign(writer.layout_.candidate_count, 0);
  writer.row_writer_ = RowWriter(writer.file_, writer.layout_, path.string());
  return writer;
}

DatasetWriter DatasetWriter::resume(const std::filesystem::path& path, const Provenance& provenance,
                                    MPI_Comm comm) {
  h5::silence_errors();
  DatasetWriter writer(path, comm);
  // Rank 0 checks everything read-only first, so a refusal changes no byte of either file.
  ResumeState state;
  agree(comm, [&] {
    if (writer.rank_ == 0) state = read_resume_state(path, provenance);
  });
  std::uint64_t count = state.done.size();
  MPI_Bcast(&count, 1, MPI_UINT64_T, 0, comm);
  state.done.resize(count);
  MPI_Bcast(state.done.data(), static_cast<int>(count), MPI_UINT8_T, 0, comm);
  agree(comm, [&] { writer.open_collective(false); });
  agree(comm, [&] { writer.layout_ = DatasetLayout::read(writer.file_); });
  agree(comm, [&] {
    if (writer.rank_ == 0) {
      writer.journal_.open(Journal::reopen(Journal::path_for(path), state.journal_bytes));
    }
  });
  writer.done_ = std::move(state.done);
  writer.damaged_ = std::move(state.damaged);
  writer.row_writer_ = RowWriter(writer.file_, writer.layout_, path.string());
  return writer;
}

void DatasetWriter::check_plan(const DatasetPlan& plan) const {
  check_open();
  agree(comm_, [&] { check_layout(file_, path_.string(), plan, layout_); });
}

std::vector<std::uint64_t> DatasetWriter::pending() const {
  std::vector<std::uint64_t> ids;
  for (std::uint64_t id = 0; id < done_.size(); ++id) {
    if (done_[id] == 0) ids.push_back(id);
  }
  return ids;
}

void DatasetWriter::write(std::span<const CandidateResult> results) {
  check_open();
  // Check locally, then over all ranks: each id once, and only pending ones.
  agree(comm_, [&] { check_results(results, layout_, done_, path_.string()); });
  const std::vector<std::uint64_t> all = gathered_ids(results, comm_);
  agree(comm_, [&] { check_once(all, path_.string(), "batch"); });
  if (all.empty()) return;

  const std::vector<const CandidateResult*> sorted = sorted_by_id(results);
  // Every rank joins the writes of every dataset that any rank touches in this batch.
  std::vector<std::uint8_t> touched = touched_by(layout_, sorted);
  MPI_Allreduce(MPI_IN_PLACE, touched.data(), static_cast<int>(touched.size()), MPI_UINT8_T,
                MPI_MAX, comm_);
  row_writer_.write_results(layout_, sorted, touched, true);

  // Commit: rows reach the disk before their done flags, the flags before the journal line.
  h5::check(H5Fflush(file_, H5F_SCOPE_GLOBAL), path_.string() + ": flushing a batch");
  row_writer_.write_done(ids_of(sorted), true);
  h5::check(H5Fflush(file_, H5F_SCOPE_GLOBAL), path_.string() + ": flushing done flags");
  agree(comm_, [&] { journal_.append_batch(all); });
  for (const std::uint64_t id : all) done_[id] = 1;
}

void DatasetWriter::commit_unit(std::span<const CandidateResult> results) {
  check_open();
  check_results(results, layout_, done_, path_.string());
  const std::vector<const CandidateResult*> sorted = sorted_by_id(results);
  const std::vector<std::uint64_t> rows = ids_of(sorted);
  check_once(rows, path_.string(), "work unit");
  if (rows.empty()) return;
  row_writer_.write_results(layout_, sorted, touched_by(layout_, sorted), false);
  row_writer_.write_done(rows, false);
  // Rows, checksums and flags on disk before the journal says so; resume takes a candidate as
  // done only when both its flag and a journal line do, so one sync covers all three.
  sync_file_.sync(path_.string() + ": cannot sync a work unit's rows");
  for (const std::uint64_t id : rows) done_[id] = 1;
  journal_.append_unit(rows);
}

void DatasetWriter::poll_journal() { journal_.poll(); }

void DatasetWriter::end_units(const std::function<void()>& while_waiting) {
  journal_.end_units(while_waiting);
}

}  // namespace grip::io
