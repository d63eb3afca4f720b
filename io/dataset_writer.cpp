#include "io/dataset_writer.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <limits>
#include <numeric>
#include <string>
#include <thread>
#include <type_traits>
#include <utility>

#include "io/checksum.hpp"
#include "io/column.hpp"
#include "io/column_values.hpp"
#include "io/dataset_columns.hpp"
#include "io/dataset_damage.hpp"
#include "io/dataset_error.hpp"

namespace grip::io {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kJournalTag = 2601;  // a work unit's ids, sent to rank 0 for its journal
constexpr int kWaitPoll = 20;      // ms between rank 0's looks while it waits for the others

int comm_rank(MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  return rank;
}

// Runs a step that involves no collective call; if it throws on any rank, every rank throws
// the message of the lowest failing rank, so no rank is left waiting in a later collective.
template <typename Step>
void agree(MPI_Comm comm, Step&& step) {
  int size = 0;
  MPI_Comm_size(comm, &size);
  std::string message;
  try {
    step();
  } catch (const std::exception& e) {
    message = e.what();
    if (message.empty()) message = "unknown error";
  }
  const int mine = message.empty() ? size : comm_rank(comm);
  int first = size;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == size) return;
  int length = static_cast<int>(message.size());
  MPI_Bcast(&length, 1, MPI_INT, first, comm);
  message.resize(static_cast<std::size_t>(length));
  MPI_Bcast(message.data(), length, MPI_CHAR, first, comm);
  throw DatasetError(message);
}

// ---- creation -------------------------------------------------------------------------------

h5::Handle group_creation() {
  h5::Handle plist = h5::plist_handle(H5Pcreate(H5P_GROUP_CREATE), "creating group properties");
  // No modification times in object headers: equal jobs give equal bytes.
  h5::check(H5Pset_obj_track_times(plist, false), "turning off time tracking");
  return plist;
}

h5::Handle make_group(hid_t location, const std::string& path) {
  const h5::Handle plist = group_creation();
  return h5::group_handle(H5Gcreate2(location, path.c_str(), H5P_DEFAULT, plist, H5P_DEFAULT),
                          "creating group " + path);
}

// A column's dataset: contiguous, its space allocated now, filled as the column says (small
// table columns now; bulky per-frame data left as the file system gives it, since it is only
// read where a done flag says it was written).
h5::Handle make_dataset(hid_t location, const Column& column, const Dims& dims, hid_t file_type,
                        hid_t memory_type) {
  const std::string path = column.name;
  const h5::Handle space =
      dims.empty()
          ? h5::space_handle(H5Screate(H5S_SCALAR), "shaping " + path)
          : h5::space_handle(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
                             "shaping " + path);
  const h5::Handle plist =
      h5::plist_handle(H5Pcreate(H5P_DATASET_CREATE), "creating dataset properties");
  h5::check(H5Pset_layout(plist, H5D_CONTIGUOUS), "choosing a contiguous layout");
  h5::check(H5Pset_alloc_time(plist, H5D_ALLOC_TIME_EARLY), "choosing early allocation");
  h5::check(H5Pset_obj_track_times(plist, false), "turning off time tracking");
  switch (column.fill) {
    case Fill::kUnset:
      break;
    case Fill::kNever:
      h5::check(H5Pset_fill_time(plist, H5D_FILL_TIME_NEVER), "choosing no fill");
      break;
    case Fill::kZero:
    case Fill::kNaN: {
      const std::array<std::byte, 8> fill = fill_bytes(column.element, column.fill);
      h5::check(H5Pset_fill_value(plist, memory_type, fill.data()), "setting a fill value");
      h5::check(H5Pset_fill_time(plist, H5D_FILL_TIME_ALLOC), "choosing fill at allocation");
      break;
    }
  }
  return h5::dataset_handle(
      H5Dcreate2(location, path.c_str(), file_type, space, H5P_DEFAULT, plist, H5P_DEFAULT),
      "creating dataset " + path);
}

std::size_t element_count(const std::vector<hsize_t>& dims) {
  return std::accumulate(dims.begin(), dims.end(), std::size_t{1},
                         [](std::size_t a, hsize_t b) { return a * b; });
}

// Writes a whole dataset from rank 0; the other ranks join the collective call with nothing.
void write_from_root(hid_t dataset, hid_t memory_type, const void* data, int rank, hid_t transfer) {
  if (element_count(h5::dims(dataset)) == 0) return;  // same on every rank
  if (rank == 0) {
    h5::check(H5Dwrite(dataset, memory_type, H5S_ALL, H5S_ALL, transfer, data), "writing data");
    return;
  }
  const h5::Handle file_space = h5::space_handle(H5Dget_space(dataset), "selecting nothing");
  h5::check(H5Sselect_none(file_space), "selecting nothing");
  const hsize_t one = 1;
  const h5::Handle memory_space =
      h5::space_handle(H5Screate_simple(1, &one, nullptr), "selecting nothing");
  h5::check(H5Sselect_none(memory_space), "selecting nothing");
  const char dummy = 0;
  h5::check(H5Dwrite(dataset, memory_type, memory_space, file_space, transfer, &dummy),
            "writing data");
}

// Creates a column's dataset in `location` and, given `values`, writes them whole from rank 0
// with their checksum.
void create_column(hid_t location, const Column& column, const Dims& dims, const Values* values,
                   int rank, hid_t transfer) {
  if (column.element == Element::kString) {
    const auto* strings = values ? &std::get<std::vector<std::string>>(*values) : nullptr;
    const std::size_t width = strings ? string_width(*strings) : 1;
    const h5::Handle type = element_type(column.element, true, width);
    const h5::Handle dataset = make_dataset(location, column, dims, type, type);
    if (strings) {
      write_from_root(dataset, type, packed_strings(*strings, width).data(), rank, transfer);
      write_whole_checksum(dataset, *values, width);
    }
    return;
  }
  const h5::Handle file_type = element_type(column.element, true);
  const h5::Handle memory_type = element_type(column.element, false);
  const h5::Handle dataset = make_dataset(location, column, dims, file_type, memory_type);
  if (values) {
    write_from_root(dataset, memory_type, number_data(*values), rank, transfer);
    write_whole_checksum(dataset, *values, 1);
  }
}

// Creates a whole-record column from the record's values.
template <typename Record>
void create_record_column(hid_t location, const Column& column, const Record& record, int rank,
                          hid_t transfer) {
  Values values = empty_values(value_index(column.element));
  column.access_to<Record>().get(record, values);
  Sizes sizes;
  sizes.count = value_count(values);
  create_column(location, column, column.extents(sizes), &values, rank, transfer);
}

// Creates a row place's column of `rows` rows shaped by `sizes`; `values`, if any, fill it whole.
void create_row_column(hid_t location, const Column& column, hsize_t rows, const Sizes& sizes,
                       const Values* values, int rank, hid_t transfer) {
  Dims dims{rows};
  const Dims extents = column.extents(sizes);
  dims.insert(dims.end(), extents.begin(), extents.end());
  create_column(location, column, dims, values, rank, transfer);
}

void write_provenance(hid_t file, const Provenance& provenance, const DatasetLayout& layout,
                      std::uint64_t objects, std::uint64_t grippers, int rank, hid_t transfer) {
  h5::write_attribute(file, "format", std::string(kFormatName));
  h5::write_attribute(file, "format_version", kFormatVersion);
  h5::write_attribute(file, "job_id", job_id(provenance.job_text, provenance.seed));
  h5::write_attribute(file, "seed", provenance.seed);
  h5::write_attribute(file, "grip_version", provenance.grip_version);
  h5::write_attribute(file, "git_revision", provenance.git_revision);
  h5::write_attribute(file, "candidate_count", layout.candidate_count);
  h5::write_attribute(file, "object_count", objects);
  h5::write_attribute(file, "gripper_count", grippers);
  h5::write_attribute(file, "closing_frames", std::uint64_t{layout.closing_frames});
  h5::write_attribute(file, "validation_frames", std::uint64_t{layout.validation_frames});
  h5::write_attribute(file, "max_hands", std::uint64_t{layout.max_hands});
  h5::write_attribute(file, "max_joints", std::uint64_t{layout.max_joints});
  h5::write_attribute(file, "max_fingers", std::uint64_t{layout.max_fingers});

  const h5::Handle group = make_group(file, "/provenance");
  h5::write_attribute(group, "job_file", provenance.job_file);
  for (const Column& column : dataset_columns()) {
    if (column.place == Place::kProvenance) {
      create_record_column(group, column, provenance, rank, transfer);
    }
  }
}

void write_object(hid_t file, std::uint32_t index, const ObjectRecord& object,
                  const DatasetLayout& layout, std::size_t gripper_count, int rank,
                  hid_t transfer) {
  const h5::Handle group = make_group(file, object_group(index));
  h5::write_attribute(group, "name", object.name);
  h5::write_attribute(group, "category", object.category);
  h5::write_attribute(group, "scale", object.scale);
  h5::write_attribute(group, "soft", std::uint64_t{object.soft});
  h5::write_attribute(group, "young_modulus", object.material.young_modulus);
  h5::write_attribute(group, "poisson_ratio", object.material.poisson_ratio);
  h5::write_attribute(group, "density", object.material.density);
  h5::write_attribute(group, "friction", object.material.friction);
  Sizes object_sizes = Sizes::of(layout);
  object_sizes.object = layout.objects[index];
  for (const Column& column : dataset_columns()) {
    if (column.place == Place::kObject) {
      create_record_column(group, column, object, rank, transfer);
    } else if (column.place == Place::kStress && object_sizes.object.stress_slots > 0) {
      create_row_column(group, column, object_sizes.object.stress_slots, object_sizes, nullptr,
                        rank, transfer);
    }
  }
  bool any_trajectory = false;
  for (std::uint32_t g = 0; g < gripper_count; ++g) {
    const hsize_t slots = layout.trajectory_slots[layout.pair(index, g)];
    if (slots == 0) continue;
    if (!any_trajectory) make_group(group, "trajectories");
    any_trajectory = true;
    const h5::Handle trajectories = make_group(file, trajectory_group(index, g));
    const Sizes sizes = Sizes::of(layout, index, g);
    for (const Column& column : dataset_columns()) {
      if (column.place == Place::kTrajectory) {
        create_row_column(trajectories, column, slots, sizes, nullptr, rank, transfer);
      }
    }
  }
}

void write_gripper(hid_t file, std::uint32_t index, const GripperRecord& gripper, int rank,
                   hid_t transfer) {
  const h5::Handle group = make_group(file, gripper_group(index));
  h5::write_attribute(group, "name", gripper.name);
  h5::write_attribute(group, "kind", gripper.kind);
  h5::write_attribute(group, "soft", std::uint64_t{gripper.soft});
  h5::write_attribute(group, "hands", std::uint64_t{gripper.hands});
  for (const Column& column : dataset_columns()) {
    if (column.place == Place::kGripper) {
      create_record_column(group, column, gripper, rank, transfer);
    }
  }
}

// Plan columns are written now; done, checksum and result columns start as their fill ("not
// written").
void write_candidate_table(hid_t file, const DatasetLayout& layout, int rank, hid_t transfer) {
  const h5::Handle group = make_group(file, "/candidates");
  const hsize_t n = layout.candidate_count;
  const Sizes sizes = Sizes::of(layout);
  for (const Column& column : dataset_columns()) {
    if (column.place == Place::kPlan) {
      Values values = empty_values(value_index(column.element));
      column.access_to<DatasetLayout>().get(layout, values);
      create_row_column(group, column, n, sizes, &values, rank, transfer);
    } else if (column.place == Place::kDone || column.place == Place::kResult ||
               column.place == Place::kChecksum) {
      create_row_column(group, column, n, sizes, nullptr, rank, transfer);
    }
  }
}

// ---- batch writes ---------------------------------------------------------------------------

// Writes one row per entry of `rows` (ascending) from `data` (rows packed in that order).
// Collectively: one call, a rank with no rows joining with an empty selection. Independently:
// one call per run of consecutive rows, each a contiguous range of the file (no read-modify-write
// of a range another rank may be writing).
void write_rows(hid_t dataset, const std::vector<std::uint64_t>& rows, hid_t memory_type,
                const void* data, hid_t transfer, bool collective) {
  if (!collective && rows.empty()) return;
  const std::vector<hsize_t> dims = h5::dims(dataset);
  const std::size_t row_size = element_count(std::vector<hsize_t>(dims.begin() + 1, dims.end()));
  if (row_size == 0) return;  // a zero-width column; the same on every rank
  const h5::Handle file_space = h5::space_handle(H5Dget_space(dataset), "selecting rows");
  h5::check(H5Sselect_none(file_space), "selecting rows");
  std::vector<hsize_t> start(dims.size(), 0);
  std::vector<hsize_t> count = dims;
  const std::size_t row_bytes = row_size * H5Tget_size(memory_type);
  for (std::size_t i = 0; i < rows.size();) {
    std::size_t j = i + 1;
    while (j < rows.size() && rows[j] == rows[j - 1] + 1) ++j;
    start[0] = rows[i];
    count[0] = j - i;
    h5::check(H5Sselect_hyperslab(file_space, collective ? H5S_SELECT_OR : H5S_SELECT_SET,
                                  start.data(), nullptr, count.data(), nullptr),
              "selecting rows");
    if (!collective) {
      const hsize_t values = (j - i) * row_size;
      const h5::Handle memory_space =
          h5::space_handle(H5Screate_simple(1, &values, nullptr), "shaping rows");
      h5::check(H5Dwrite(dataset, memory_type, memory_space, file_space, transfer,
                         static_cast<const std::byte*>(data) + i * row_bytes),
                "writing rows");
    }
    i = j;
  }
  if (!collective) return;
  const hsize_t total = std::max<hsize_t>(rows.size() * row_size, 1);
  const h5::Handle memory_space =
      h5::space_handle(H5Screate_simple(1, &total, nullptr), "shaping rows");
  if (rows.empty()) h5::check(H5Sselect_none(memory_space), "selecting nothing");
  const char dummy = 0;
  h5::check(H5Dwrite(dataset, memory_type, memory_space, file_space, transfer,
                     rows.empty() ? static_cast<const void*>(&dummy) : data),
            "writing rows");
}

// Packs one column's rows of `records` (in order): each record's values, padded per hand to
// the table's widths where the column has hands.
template <typename Record>
Values packed_rows(const Column& column, const std::vector<const Record*>& records,
                   const DatasetLayout& layout) {
  const auto& access = column.access_to<Record>();
  Values packed = empty_values(value_index(column.element));
  const Sizes table = Sizes::of(layout);
  for (const Record* record : records) {
    if constexpr (std::is_same_v<Record, CandidateResult>) {
      if (column.per_hand != nullptr) {
        Values values = empty_values(value_index(column.element));
        access.get(*record, values);
        const DatasetLayout::Gripper& gripper = layout.grippers[layout.gripper[record->record.id]];
        append_padded(packed, values, gripper.hands, column.per_hand(gripper), table.max_hands,
                      row_size(column, table) / table.max_hands,
                      column.fill == Fill::kNaN ? kNaN : 0.0);
        continue;
      }
    }
    access.get(*record, packed);
  }
  return packed;
}

// A trajectory field named like a candidate table column is "trajectory NAME" in messages.
std::string field_label(const Column& column) {
  const std::string name = column.name;
  if (column.place != Place::kTrajectory) return name;
  const auto columns = dataset_columns();
  const bool shared = std::any_of(columns.begin(), columns.end(), [&](const Column& other) {
    return other.place == Place::kResult && name == other.name;
  });
  return shared ? "trajectory " + name : name;
}

std::string check_result(const CandidateResult& result, const DatasetLayout& layout,
                         const std::vector<std::uint8_t>& done) {
  const CandidateRecord& r = result.record;
  const std::string which = "candidate " + std::to_string(r.id);
  if (r.id >= layout.candidate_count) {
    return which + " is outside the dataset's " + std::to_string(layout.candidate_count) +
           " candidates";
  }
  if (done[r.id] != 0) return which + " is already written; a record is written once";
  const Sizes sizes = Sizes::of_candidate(layout, r.id);
  // The first column of `place` whose values in `record` do not fill its row, or "".
  const auto size_problem = [&](Place place, const auto& record) -> std::string {
    using Record = std::remove_cvref_t<decltype(record)>;
    for (const Column& column : dataset_columns()) {
      if (column.place != place) continue;
      const std::size_t got = column.access_to<Record>().size(record);
      const std::size_t want = record_size(column, sizes);
      if (got != want) {
        return which + ": " + field_label(column) + " has " + std::to_string(got) +
               " values, expected " + std::to_string(want);
      }
    }
    return "";
  };
  std::string problem = size_problem(Place::kResult, result);
  if (!problem.empty()) return problem;
  if (result.trajectory) {
    if (layout.frame_slot[r.id] < 0) return which + " has a trajectory but no frame slot";
    problem = size_problem(Place::kTrajectory, *result.trajectory);
    if (!problem.empty()) return problem;
  }
  if (result.stress) {
    if (layout.stress_slot[r.id] < 0) return which + " has stress but no stress slot";
    problem = size_problem(Place::kStress, result);
    if (!problem.empty()) return problem;
  }
  return "";
}

// Results in id order: a union of row hyperslabs is written in row order.
std::vector<const CandidateResult*> sorted_by_id(std::span<const CandidateResult> results) {
  std::vector<const CandidateResult*> sorted;
  for (const CandidateResult& result : results) sorted.push_back(&result);
  std::sort(sorted.begin(), sorted.end(),
            [](const auto* a, const auto* b) { return a->record.id < b->record.id; });
  return sorted;
}

std::vector<std::uint64_t> ids_of(const std::vector<const CandidateResult*>& sorted) {
  std::vector<std::uint64_t> ids;
  for (const auto* result : sorted) ids.push_back(result->record.id);
  return ids;
}

// Receives the work unit `status` announces and adds its ids to `ids`.
void receive_unit(const MPI_Status& status, MPI_Comm comm, std::vector<std::uint64_t>& ids) {
  int count = 0;
  MPI_Get_count(&status, MPI_UINT64_T, &count);
  const std::size_t at = ids.size();
  ids.resize(at + static_cast<std::size_t>(count));
  MPI_Recv(ids.data() + at, count, MPI_UINT64_T, status.MPI_SOURCE, kJournalTag, comm,
           MPI_STATUS_IGNORE);
}

}  // namespace

DatasetWriter::DatasetWriter(std::filesystem::path path, DatasetLayout layout, MPI_Comm comm)
    : path_(std::move(path)), layout_(std::move(layout)), comm_(comm), rank_(comm_rank(comm)) {}

DatasetWriter::DatasetWriter(DatasetWriter&&) noexcept = default;
DatasetWriter& DatasetWriter::operator=(DatasetWriter&&) noexcept = default;

DatasetWriter::~DatasetWriter() { close(); }

void DatasetWriter::close() {
  row_datasets_.clear();
  transfer_.reset();
  independent_.reset();
  file_.reset();
  sync_file_ = SyncFile();
  journal_.reset();
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
  transfer_ = h5::plist_handle(H5Pcreate(H5P_DATASET_XFER), "creating transfer properties");
  h5::check(H5Pset_dxpl_mpio(transfer_, H5FD_MPIO_COLLECTIVE), "choosing collective transfers");
  independent_ = h5::plist_handle(H5Pcreate(H5P_DATASET_XFER), "creating transfer properties");
  h5::check(H5Pset_dxpl_mpio(independent_, H5FD_MPIO_INDEPENDENT),
            "choosing independent transfers");
  const int fd = ::open(name.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0)
    throw DatasetError(name + ": cannot open the dataset to sync: " + std::strerror(errno));
  sync_file_ = SyncFile(fd);
}

// Every dataset that rows are written into, opened once by every rank together: the work units'
// independent writes then touch raw data only, no metadata.
void DatasetWriter::open_row_datasets() {
  const auto open = [&](const std::string& path) {
    row_datasets_.emplace(path, h5::open_dataset(file_, path));
  };
  for (const Column& column : dataset_columns()) {
    if (column.place == Place::kResult || column.place == Place::kDone ||
        column.place == Place::kChecksum) {
      open(std::string("/candidates/") + column.name);
    }
  }
  const std::uint32_t grippers = static_cast<std::uint32_t>(layout_.grippers.size());
  for (std::uint32_t o = 0; o < layout_.objects.size(); ++o) {
    for (const Column& column : dataset_columns()) {
      if (column.place == Place::kStress && layout_.objects[o].stress_slots > 0) {
        open(object_group(o) + "/" + column.name);
      }
    }
    for (std::uint32_t g = 0; g < grippers; ++g) {
      if (layout_.trajectory_slots[layout_.pair(o, g)] == 0) continue;
      for (const Column& column : dataset_columns()) {
        if (column.place == Place::kTrajectory) open(trajectory_group(o, g) + "/" + column.name);
      }
    }
  }
}

hid_t DatasetWriter::row_dataset(const std::string& path) const {
  const auto found = row_datasets_.find(path);
  if (found == row_datasets_.end()) throw DatasetError(path_.string() + ": no dataset " + path);
  return found->second;
}

DatasetWriter DatasetWriter::create(const std::filesystem::path& path, const DatasetPlan& plan,
                                    const Provenance& provenance, MPI_Comm comm) {
  h5::silence_errors();
  DatasetWriter writer(path, DatasetLayout{}, comm);
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
  const DatasetLayout& layout = writer.layout_;
  const int rank = writer.rank_;
  const hid_t transfer = writer.transfer_;
  write_provenance(writer.file_, provenance, layout, plan.objects.size(), plan.grippers.size(),
                   rank, transfer);
  make_group(writer.file_, "/objects");
  for (std::uint32_t o = 0; o < plan.objects.size(); ++o) {
    write_object(writer.file_, o, plan.objects[o], layout, plan.grippers.size(), rank, transfer);
  }
  make_group(writer.file_, "/grippers");
  for (std::uint32_t g = 0; g < plan.grippers.size(); ++g) {
    write_gripper(writer.file_, g, plan.grippers[g], rank, transfer);
  }
  write_candidate_table(writer.file_, layout, rank, transfer);
  h5::check(H5Fflush(writer.file_, H5F_SCOPE_GLOBAL), path.string() + ": flushing the layout");
  // The journal's existence says the layout is complete: a crash before this line leaves a
  // dataset that resume() refuses, never one that looks resumable but is half made.
  agree(comm, [&] {
    if (rank == 0) {
      writer.journal_.emplace(Journal::create(journal, job_id(provenance.job_text, provenance.seed),
                                              layout.candidate_count));
    }
  });
  writer.done_.assign(layout.candidate_count, 0);
  writer.open_row_datasets();
  return writer;
}

DatasetWriter DatasetWriter::resume(const std::filesystem::path& path, const Provenance& provenance,
                                    MPI_Comm comm) {
  h5::silence_errors();
  DatasetWriter writer(path, DatasetLayout{}, comm);
  const std::filesystem::path journal_path = Journal::path_for(path);
  const std::string name = path.string();
  std::vector<std::uint8_t> done;
  std::uint64_t journal_bytes = 0;
  // Rank 0 checks everything read-only first, so a refusal changes no byte of either file.
  agree(comm, [&] {
    if (writer.rank_ != 0) return;
    if (!std::filesystem::exists(path)) {
      throw DatasetError(name + ": no such dataset to resume; run without --resume to create it");
    }
    if (H5Fis_hdf5(name.c_str()) <= 0) {
      throw DatasetError(name +
                         ": not an HDF5 file, so not a grip dataset; nothing was "
                         "changed (choose another output file)");
    }
    const h5::Handle file = h5::file_handle(
        H5Fopen(name.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT),
        name +
            ": the file is damaged or truncated and cannot be resumed; nothing was changed "
            "(remove it and its journal to start again)");
    DatasetLayout layout;
    try {
      layout = DatasetLayout::read(file);
    } catch (const DatasetError& e) {
      throw DatasetError(name + ": cannot resume: " + e.what() + "; nothing was changed");
    }
    const std::string wanted = job_id(provenance.job_text, provenance.seed);
    const std::string found = h5::read_string_attribute(file, "job_id");
    if (found != wanted) {
      throw DatasetError(
          name + ": made by another job (job id " + found.substr(0, 12) + ", seed " +
          std::to_string(h5::read_uint_attribute(file, "seed")) +
          "), not by this job file and "
          "seed (job id " +
          wanted.substr(0, 12) + ", seed " + std::to_string(provenance.seed) +
          "); nothing was changed. Resume with the job and seed that made it, or write to a "
          "new file");
    }
    const Journal::Contents journal = Journal::read(journal_path);
    if (journal.job_id != wanted || journal.candidate_count != layout.candidate_count) {
      throw DatasetError(journal_path.string() +
                         ": the journal belongs to another dataset "
                         "(job id " +
                         journal.job_id.substr(0, 12) + ", " +
                         std::to_string(journal.candidate_count) +
                         " candidates); nothing was "
                         "changed");
    }
    const h5::Handle flags = h5::dataset_handle(H5Dopen2(file, "/candidates/done", H5P_DEFAULT),
                                                name + ": opening the done flags");
    const std::vector<std::uint8_t> in_file = h5::read_all<std::uint8_t>(flags, H5T_NATIVE_UINT8);
    // Done means both: the flag (set after the rows were flushed) and the journal line
    // (written after the flags were flushed). Anything else is redone.
    std::vector<std::uint8_t> journaled(layout.candidate_count, 0);
    for (const std::uint64_t id : journal.done) journaled[id] = 1;
    done.assign(layout.candidate_count, 0);
    for (std::size_t id = 0; id < done.size(); ++id) done[id] = in_file[id] && journaled[id];
    // A committed row whose bytes no longer match its checksums is redone.
    try {
      writer.damaged_ = find_damage(file, layout, done);
    } catch (const DatasetError& e) {
      throw DatasetError(name + ": cannot resume: " + e.what() + "; nothing was changed");
    }
    for (const Damage& damage : writer.damaged_) done[damage.candidate] = 0;
    journal_bytes = journal.valid_bytes;
  });
  std::uint64_t count = done.size();
  MPI_Bcast(&count, 1, MPI_UINT64_T, 0, comm);
  done.resize(count);
  MPI_Bcast(done.data(), static_cast<int>(count), MPI_UINT8_T, 0, comm);
  agree(comm, [&] { writer.open_collective(false); });
  agree(comm, [&] { writer.layout_ = DatasetLayout::read(writer.file_); });
  agree(comm, [&] {
    if (writer.rank_ == 0) writer.journal_.emplace(Journal::reopen(journal_path, journal_bytes));
  });
  writer.done_ = std::move(done);
  writer.open_row_datasets();
  return writer;
}

std::vector<std::uint64_t> DatasetWriter::pending() const {
  std::vector<std::uint64_t> ids;
  for (std::uint64_t id = 0; id < done_.size(); ++id) {
    if (done_[id] == 0) ids.push_back(id);
  }
  return ids;
}

void DatasetWriter::write(std::span<const CandidateResult> results) {
  if (file_.get() < 0) throw DatasetError(path_.string() + ": the writer is closed");
  // Check locally, then over all ranks: each id once, and only pending ones.
  agree(comm_, [&] {
    for (const CandidateResult& result : results) {
      const std::string problem = check_result(result, layout_, done_);
      if (!problem.empty()) throw DatasetError(path_.string() + ": " + problem);
    }
  });
  std::vector<std::uint64_t> mine;
  for (const CandidateResult& result : results) mine.push_back(result.record.id);
  int size = 0;
  MPI_Comm_size(comm_, &size);
  const int my_count = static_cast<int>(mine.size());
  std::vector<int> counts(static_cast<std::size_t>(size));
  MPI_Allgather(&my_count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm_);
  std::vector<int> offsets(counts.size(), 0);
  std::partial_sum(counts.begin(), counts.end() - 1, offsets.begin() + 1);
  std::vector<std::uint64_t> all(static_cast<std::size_t>(offsets.back() + counts.back()));
  MPI_Allgatherv(mine.data(), my_count, MPI_UINT64_T, all.data(), counts.data(), offsets.data(),
                 MPI_UINT64_T, comm_);
  std::sort(all.begin(), all.end());
  agree(comm_, [&] {
    const auto repeated = std::adjacent_find(all.begin(), all.end());
    if (repeated != all.end()) {
      throw DatasetError(path_.string() + ": candidate " + std::to_string(*repeated) +
                         " was handed to the writer twice in one batch");
    }
  });
  if (all.empty()) return;

  const std::vector<const CandidateResult*> sorted = sorted_by_id(results);
  // Every rank joins the writes of every dataset that any rank touches in this batch.
  std::vector<std::uint8_t> touched = touched_by(sorted);
  MPI_Allreduce(MPI_IN_PLACE, touched.data(), static_cast<int>(touched.size()), MPI_UINT8_T,
                MPI_MAX, comm_);
  write_result_rows(sorted, touched, true);

  // Commit: rows reach the disk before their done flags, the flags before the journal line.
  h5::check(H5Fflush(file_, H5F_SCOPE_GLOBAL), path_.string() + ": flushing a batch");
  const std::vector<std::uint64_t> rows = ids_of(sorted);
  const std::vector<std::uint8_t> ones(rows.size(), 1);
  write_rows(row_dataset("/candidates/done"), rows, H5T_NATIVE_UINT8, ones.data(), transfer_, true);
  h5::check(H5Fflush(file_, H5F_SCOPE_GLOBAL), path_.string() + ": flushing done flags");
  agree(comm_, [&] {
    if (rank_ == 0) journal_->append(all);
  });
  for (const std::uint64_t id : all) done_[id] = 1;
}

void DatasetWriter::commit_unit(std::span<const CandidateResult> results) {
  if (file_.get() < 0) throw DatasetError(path_.string() + ": the writer is closed");
  for (const CandidateResult& result : results) {
    const std::string problem = check_result(result, layout_, done_);
    if (!problem.empty()) throw DatasetError(path_.string() + ": " + problem);
  }
  const std::vector<const CandidateResult*> sorted = sorted_by_id(results);
  const std::vector<std::uint64_t> rows = ids_of(sorted);
  if (const auto repeated = std::adjacent_find(rows.begin(), rows.end()); repeated != rows.end()) {
    throw DatasetError(path_.string() + ": candidate " + std::to_string(*repeated) +
                       " was handed to the writer twice in one work unit");
  }
  if (rows.empty()) return;
  write_result_rows(sorted, touched_by(sorted), false);
  const std::vector<std::uint8_t> ones(rows.size(), 1);
  write_rows(row_dataset("/candidates/done"), rows, H5T_NATIVE_UINT8, ones.data(), independent_,
             false);
  // Rows, checksums and flags on disk before the journal says so; resume takes a candidate as
  // done only when both its flag and a journal line do, so one sync covers all three.
  if (::fdatasync(sync_file_.get()) != 0) {
    throw DatasetError(path_.string() +
                       ": cannot sync a work unit's rows: " + std::strerror(errno));
  }
  for (const std::uint64_t id : rows) done_[id] = 1;
  if (rank_ == 0) {
    unjournaled_.insert(unjournaled_.end(), rows.begin(), rows.end());
    append_to_journal();
    return;
  }
  sends_.push_back({MPI_REQUEST_NULL, rows});
  Send& send = sends_.back();
  MPI_Isend(send.ids.data(), static_cast<int>(send.ids.size()), MPI_UINT64_T, 0, kJournalTag, comm_,
            &send.request);
  ++units_sent_;
  poll_journal();
}

void DatasetWriter::poll_journal() {
  if (rank_ != 0) {
    std::erase_if(sends_, [](Send& send) {
      int done = 0;
      MPI_Test(&send.request, &done, MPI_STATUS_IGNORE);
      return done != 0;
    });
    return;
  }
  for (;;) {
    int arrived = 0;
    MPI_Status status;
    MPI_Iprobe(MPI_ANY_SOURCE, kJournalTag, comm_, &arrived, &status);
    if (!arrived) break;
    receive_unit(status, comm_, unjournaled_);
    ++units_received_;
  }
  append_to_journal();
}

void DatasetWriter::end_units(const std::function<void()>& while_waiting) {
  std::uint64_t total = 0;
  MPI_Request request;
  MPI_Ireduce(&units_sent_, &total, 1, MPI_UINT64_T, MPI_SUM, 0, comm_, &request);
  if (rank_ != 0) {
    MPI_Wait(&request, MPI_STATUS_IGNORE);
    for (Send& send : sends_) MPI_Wait(&send.request, MPI_STATUS_IGNORE);
    sends_.clear();
    return;
  }
  for (int done = 0;;) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    poll_journal();
    if (done) break;
    while_waiting();
    std::this_thread::sleep_for(std::chrono::milliseconds(kWaitPoll));
  }
  // Every rank has sent all it will: take the messages still on their way.
  for (; units_received_ < total; ++units_received_) {
    MPI_Status status;
    MPI_Probe(MPI_ANY_SOURCE, kJournalTag, comm_, &status);
    receive_unit(status, comm_, unjournaled_);
  }
  append_to_journal();
}

void DatasetWriter::append_to_journal() {
  if (unjournaled_.empty()) return;
  journal_->append(unjournaled_);
  unjournaled_.clear();
}

std::vector<std::uint8_t> DatasetWriter::touched_by(
    const std::vector<const CandidateResult*>& sorted) const {
  const std::size_t pairs = layout_.trajectory_slots.size();
  std::vector<std::uint8_t> touched(pairs + layout_.objects.size(), 0);
  for (const auto* result : sorted) {
    const std::uint64_t id = result->record.id;
    if (result->trajectory) touched[layout_.pair(layout_.object[id], layout_.gripper[id])] = 1;
    if (result->stress) touched[pairs + layout_.object[id]] = 1;
  }
  return touched;
}

void DatasetWriter::write_result_rows(const std::vector<const CandidateResult*>& sorted,
                                      const std::vector<std::uint8_t>& touched, bool collective) {
  const hid_t transfer = collective ? transfer_.get() : independent_.get();
  const std::vector<std::uint64_t> rows = ids_of(sorted);
  // Each row's checksum per column, written beside the rows (this rank's rows in `sorted` order).
  const std::size_t entries = checksum_entries();
  std::vector<std::uint32_t> checksums(rows.size() * entries, 0);
  // Writes `values`, rows of `row_size` packed in order for the results at `positions` in
  // `sorted`, and records their checksums.
  const auto write_checksummed =
      [&](const Column& column, const std::string& path, const std::vector<std::uint64_t>& at,
          const std::vector<std::size_t>& positions, std::size_t row_size, const Values& values) {
        const std::size_t entry = checksum_entry(column);
        for (std::size_t i = 0; i < positions.size(); ++i) {
          checksums[positions[i] * entries + entry] = row_checksum(values, i * row_size, row_size);
        }
        const h5::Handle memory_type = element_type(column.element, false);
        write_rows(row_dataset(path), at, memory_type, number_data(values), transfer, collective);
      };
  std::vector<std::size_t> all_positions(sorted.size());
  std::iota(all_positions.begin(), all_positions.end(), std::size_t{0});
  const Sizes table = Sizes::of(layout_);
  for (const Column& column : dataset_columns()) {
    if (column.place != Place::kResult) continue;
    write_checksummed(column, std::string("/candidates/") + column.name, rows, all_positions,
                      row_size(column, table), packed_rows(column, sorted, layout_));
  }

  // Trajectories and stress live in per-object datasets, written in the same order everywhere.
  const std::size_t pairs = layout_.trajectory_slots.size();
  const std::uint32_t gripper_count = static_cast<std::uint32_t>(layout_.grippers.size());
  for (std::size_t p = 0; p < pairs; ++p) {
    if (!touched[p]) continue;
    const auto o = static_cast<std::uint32_t>(p / gripper_count);
    const auto g = static_cast<std::uint32_t>(p % gripper_count);
    std::vector<std::uint64_t> slots;
    std::vector<std::size_t> positions;
    std::vector<const TrajectoryRecord*> trajectories;
    for (std::size_t i = 0; i < sorted.size(); ++i) {
      const std::uint64_t id = sorted[i]->record.id;
      if (sorted[i]->trajectory && layout_.pair(layout_.object[id], layout_.gripper[id]) == p) {
        slots.push_back(static_cast<std::uint64_t>(layout_.frame_slot[id]));
        positions.push_back(i);
        trajectories.push_back(&*sorted[i]->trajectory);
      }
    }
    const std::string group = trajectory_group(o, g) + "/";
    const Sizes sizes = Sizes::of(layout_, o, g);
    for (const Column& column : dataset_columns()) {
      if (column.place != Place::kTrajectory) continue;
      write_checksummed(column, group + column.name, slots, positions, row_size(column, sizes),
                        packed_rows(column, trajectories, layout_));
    }
  }
  for (std::uint32_t o = 0; o < layout_.objects.size(); ++o) {
    if (!touched[pairs + o]) continue;
    std::vector<std::uint64_t> slots;
    std::vector<std::size_t> positions;
    std::vector<const CandidateResult*> stressed;
    for (std::size_t i = 0; i < sorted.size(); ++i) {
      const std::uint64_t id = sorted[i]->record.id;
      if (sorted[i]->stress && layout_.object[id] == o) {
        slots.push_back(static_cast<std::uint64_t>(layout_.stress_slot[id]));
        positions.push_back(i);
        stressed.push_back(sorted[i]);
      }
    }
    const std::string group = object_group(o) + "/";
    Sizes sizes = table;
    sizes.object = layout_.objects[o];
    for (const Column& column : dataset_columns()) {
      if (column.place != Place::kStress) continue;
      write_checksummed(column, group + column.name, slots, positions, row_size(column, sizes),
                        packed_rows(column, stressed, layout_));
    }
  }
  write_rows(row_dataset("/candidates/checksum"), rows, H5T_NATIVE_UINT32, checksums.data(),
             transfer, collective);
}

DatasetWriter::SyncFile::SyncFile(SyncFile&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}

DatasetWriter::SyncFile& DatasetWriter::SyncFile::operator=(SyncFile&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = std::exchange(other.fd_, -1);
  }
  return *this;
}

DatasetWriter::SyncFile::~SyncFile() {
  if (fd_ >= 0) ::close(fd_);
}

}  // namespace grip::io
