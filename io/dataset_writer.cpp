#include "io/dataset_writer.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <string>
#include <type_traits>
#include <utility>

#include "io/dataset_error.hpp"
#include "io/enum_types.hpp"

namespace grip::io {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

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

// A contiguous dataset whose space is allocated now. With `fill`, every element is set to it
// now (small table columns); without, the space is left as the file system gives it (bulky
// per-frame data, which is only read where a done flag says it was written).
h5::Handle make_dataset(hid_t location, const std::string& path, hid_t file_type,
                        const std::vector<hsize_t>& dims, hid_t fill_type = -1,
                        const void* fill = nullptr) {
  const h5::Handle space = h5::space_handle(
      H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), "shaping " + path);
  const h5::Handle plist =
      h5::plist_handle(H5Pcreate(H5P_DATASET_CREATE), "creating dataset properties");
  h5::check(H5Pset_layout(plist, H5D_CONTIGUOUS), "choosing a contiguous layout");
  h5::check(H5Pset_alloc_time(plist, H5D_ALLOC_TIME_EARLY), "choosing early allocation");
  h5::check(H5Pset_obj_track_times(plist, false), "turning off time tracking");
  if (fill != nullptr) {
    h5::check(H5Pset_fill_value(plist, fill_type, fill), "setting a fill value");
    h5::check(H5Pset_fill_time(plist, H5D_FILL_TIME_ALLOC), "choosing fill at allocation");
  } else {
    h5::check(H5Pset_fill_time(plist, H5D_FILL_TIME_NEVER), "choosing no fill");
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

template <typename T>
void make_and_write(hid_t location, const std::string& path, hid_t file_type, hid_t memory_type,
                    const std::vector<hsize_t>& dims, const std::vector<T>& data, int rank,
                    hid_t transfer) {
  const h5::Handle dataset = make_dataset(location, path, file_type, dims);
  write_from_root(dataset, memory_type, data.data(), rank, transfer);
}

void write_strings(hid_t location, const std::string& path, const std::vector<hsize_t>& dims,
                   const std::vector<std::string>& values, int rank, hid_t transfer) {
  std::size_t width = 1;
  for (const auto& value : values) width = std::max(width, value.size());
  std::vector<char> packed(values.size() * width, '\0');
  for (std::size_t i = 0; i < values.size(); ++i) {
    std::copy(values[i].begin(), values[i].end(), packed.begin() + i * width);
  }
  const h5::Handle type = h5::string_type(width);
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
  const h5::Handle dataset = h5::dataset_handle(
      H5Dcreate2(location, path.c_str(), type, space, H5P_DEFAULT, plist, H5P_DEFAULT),
      "creating dataset " + path);
  write_from_root(dataset, type, packed.data(), rank, transfer);
}

hsize_t as_hsize(std::uint64_t n) { return static_cast<hsize_t>(n); }

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
  write_strings(group, "job_text", {}, {provenance.job_text}, rank, transfer);
  std::vector<std::string> table;
  for (const Parameter& parameter : provenance.parameters) {
    table.push_back(parameter.key);
    table.push_back(parameter.value);
  }
  write_strings(group, "parameters", {as_hsize(provenance.parameters.size()), 2}, table, rank,
                transfer);
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
  const hsize_t n = object.vertex_count();
  make_and_write(group, "vertices", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {n, 3}, object.vertices,
                 rank, transfer);
  make_and_write(group, "triangles", H5T_STD_I32LE, H5T_NATIVE_INT32,
                 {object.triangles.size() / 3, 3}, object.triangles, rank, transfer);
  make_and_write(group, "tets", H5T_STD_I32LE, H5T_NATIVE_INT32, {object.tet_count(), 4},
                 object.tets, rank, transfer);
  const DatasetLayout::Object& sizes = layout.objects[index];
  if (sizes.stress_slots > 0) {
    make_dataset(group, "stress", H5T_IEEE_F32LE, {sizes.stress_slots, sizes.tets});
  }
  const hsize_t frames = layout.frames();
  bool any_trajectory = false;
  for (std::uint32_t g = 0; g < gripper_count; ++g) {
    const hsize_t slots = layout.trajectory_slots[layout.pair(index, g)];
    if (slots == 0) continue;
    if (!any_trajectory) make_group(group, "trajectories");
    any_trajectory = true;
    const DatasetLayout::Gripper& gripper = layout.grippers[g];
    const h5::Handle trajectories = make_group(file, trajectory_group(index, g));
    const hsize_t hands = gripper.hands;
    make_dataset(trajectories, "object_vertices", H5T_IEEE_F32LE, {slots, frames, n, 3});
    make_dataset(trajectories, "gripper_vertices", H5T_IEEE_F32LE,
                 {slots, frames, hands * gripper.vertices, 3});
    make_dataset(trajectories, "contact_forces", H5T_IEEE_F32LE, {slots, frames, n, 3});
    make_dataset(trajectories, "friction_forces", H5T_IEEE_F32LE, {slots, frames, n, 3});
    make_dataset(trajectories, "object_poses", H5T_IEEE_F64LE, {slots, frames, 3, 4});
    make_dataset(trajectories, "hand_poses", H5T_IEEE_F64LE, {slots, frames, hands, 3, 4});
    make_dataset(trajectories, "joints", H5T_IEEE_F64LE, {slots, frames, hands, gripper.joints});
  }
}

void write_gripper(hid_t file, std::uint32_t index, const GripperRecord& gripper, int rank,
                   hid_t transfer) {
  const h5::Handle group = make_group(file, gripper_group(index));
  h5::write_attribute(group, "name", gripper.name);
  h5::write_attribute(group, "kind", gripper.kind);
  h5::write_attribute(group, "soft", std::uint64_t{gripper.soft});
  h5::write_attribute(group, "hands", std::uint64_t{gripper.hands});
  write_strings(group, "joint_names", {gripper.joint_names.size()}, gripper.joint_names, rank,
                transfer);
  write_strings(group, "finger_names", {gripper.finger_names.size()}, gripper.finger_names, rank,
                transfer);
  make_and_write(group, "vertices", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {gripper.vertex_count(), 3},
                 gripper.vertices, rank, transfer);
  make_and_write(group, "triangles", H5T_STD_I32LE, H5T_NATIVE_INT32,
                 {gripper.triangles.size() / 3, 3}, gripper.triangles, rank, transfer);
}

void write_candidate_table(hid_t file, const DatasetLayout& layout, int rank, hid_t transfer) {
  const h5::Handle group = make_group(file, "/candidates");
  const hsize_t n = layout.candidate_count;
  const hsize_t hands = layout.max_hands;
  make_and_write(group, "object", H5T_STD_U32LE, H5T_NATIVE_UINT32, {n}, layout.object, rank,
                 transfer);
  make_and_write(group, "gripper", H5T_STD_U32LE, H5T_NATIVE_UINT32, {n}, layout.gripper, rank,
                 transfer);
  make_and_write(group, "frame_slot", H5T_STD_I64LE, H5T_NATIVE_INT64, {n}, layout.frame_slot, rank,
                 transfer);
  make_and_write(group, "stress_slot", H5T_STD_I64LE, H5T_NATIVE_INT64, {n}, layout.stress_slot,
                 rank, transfer);

  // Result columns start as "not written": zero flags and counts, NaN numbers.
  const std::uint8_t zero8 = 0;
  const std::uint32_t zero32 = 0;
  const h5::Handle status_file = status_type(true);
  const h5::Handle status_memory = status_type(false);
  const h5::Handle failure_file = failure_kind_type(true);
  const h5::Handle failure_memory = failure_kind_type(false);
  make_dataset(group, "done", H5T_STD_U8LE, {n}, H5T_NATIVE_UINT8, &zero8);
  make_dataset(group, "status", status_file, {n}, status_memory, &zero8);
  make_dataset(group, "failure", failure_file, {n}, failure_memory, &zero8);
  make_dataset(group, "hand_poses", H5T_IEEE_F64LE, {n, hands, 3, 4}, H5T_NATIVE_DOUBLE, &kNaN);
  make_dataset(group, "joints", H5T_IEEE_F64LE, {n, hands, layout.max_joints}, H5T_NATIVE_DOUBLE,
               &kNaN);
  make_dataset(group, "d1", H5T_IEEE_F64LE, {n}, H5T_NATIVE_DOUBLE, &kNaN);
  make_dataset(group, "d2", H5T_IEEE_F64LE, {n}, H5T_NATIVE_DOUBLE, &kNaN);
  make_dataset(group, "displacement", H5T_IEEE_F64LE, {n, 6}, H5T_NATIVE_DOUBLE, &kNaN);
  make_dataset(group, "closing_forces", H5T_IEEE_F64LE, {n, hands, layout.max_fingers},
               H5T_NATIVE_DOUBLE, &kNaN);
  make_dataset(group, "newton_steps", H5T_STD_U32LE, {n}, H5T_NATIVE_UINT32, &zero32);
  make_dataset(group, "newton_iterations", H5T_STD_U32LE, {n}, H5T_NATIVE_UINT32, &zero32);
  make_dataset(group, "newton_max_iterations", H5T_STD_U32LE, {n}, H5T_NATIVE_UINT32, &zero32);
  make_dataset(group, "wall_time", H5T_IEEE_F64LE, {n}, H5T_NATIVE_DOUBLE, &kNaN);
  make_dataset(group, "trajectory_written", H5T_STD_U8LE, {n}, H5T_NATIVE_UINT8, &zero8);
  make_dataset(group, "stress_written", H5T_STD_U8LE, {n}, H5T_NATIVE_UINT8, &zero8);
}

// ---- batch writes ---------------------------------------------------------------------------

// Writes one row per entry of `rows` (ascending) from `data` (rows packed in that order), as a
// collective call; a rank with no rows joins with an empty selection.
void write_rows(hid_t location, const std::string& path, const std::vector<std::uint64_t>& rows,
                hid_t memory_type, const void* data, hid_t transfer) {
  const h5::Handle dataset =
      h5::dataset_handle(H5Dopen2(location, path.c_str(), H5P_DEFAULT), "opening " + path);
  const std::vector<hsize_t> dims = h5::dims(dataset);
  const std::size_t row_size = element_count(std::vector<hsize_t>(dims.begin() + 1, dims.end()));
  if (row_size == 0) return;  // a zero-width column; the same on every rank
  const h5::Handle file_space = h5::space_handle(H5Dget_space(dataset), "selecting " + path);
  h5::check(H5Sselect_none(file_space), "selecting " + path);
  std::vector<hsize_t> start(dims.size(), 0);
  std::vector<hsize_t> count = dims;
  for (std::size_t i = 0; i < rows.size();) {
    std::size_t j = i + 1;
    while (j < rows.size() && rows[j] == rows[j - 1] + 1) ++j;
    start[0] = rows[i];
    count[0] = j - i;
    h5::check(H5Sselect_hyperslab(file_space, H5S_SELECT_OR, start.data(), nullptr, count.data(),
                                  nullptr),
              "selecting rows of " + path);
    i = j;
  }
  const hsize_t total = std::max<hsize_t>(rows.size() * row_size, 1);
  const h5::Handle memory_space =
      h5::space_handle(H5Screate_simple(1, &total, nullptr), "shaping rows of " + path);
  if (rows.empty()) h5::check(H5Sselect_none(memory_space), "selecting nothing");
  const char dummy = 0;
  h5::check(H5Dwrite(dataset, memory_type, memory_space, file_space, transfer,
                     rows.empty() ? static_cast<const void*>(&dummy) : data),
            "writing rows of " + path);
}

// Copies `values` into a row of `width` elements, NaN-padded.
void pad_row(std::vector<double>& out, const std::vector<double>& values, std::size_t width) {
  out.insert(out.end(), values.begin(), values.end());
  out.insert(out.end(), width - values.size(), kNaN);
}

// Hands of `per_hand` values padded to the table's widths: [max_hands][width].
void pad_hands(std::vector<double>& out, const std::vector<double>& values, std::uint32_t hands,
               std::size_t per_hand, std::uint32_t max_hands, std::size_t width) {
  for (std::uint32_t h = 0; h < max_hands; ++h) {
    if (h < hands) {
      const auto begin = values.begin() + static_cast<std::ptrdiff_t>(h * per_hand);
      out.insert(out.end(), begin, begin + static_cast<std::ptrdiff_t>(per_hand));
      out.insert(out.end(), width - per_hand, kNaN);
    } else {
      out.insert(out.end(), width, kNaN);
    }
  }
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
  const DatasetLayout::Gripper& gripper = layout.grippers[layout.gripper[r.id]];
  const DatasetLayout::Object& object = layout.objects[layout.object[r.id]];
  const auto size_error = [&](const char* field, std::size_t got, std::size_t want) {
    return which + ": " + field + " has " + std::to_string(got) + " values, expected " +
           std::to_string(want);
  };
  if (r.hand_poses.size() != 12u * gripper.hands) {
    return size_error("hand_poses", r.hand_poses.size(), 12u * gripper.hands);
  }
  if (r.joints.size() != std::size_t{gripper.joints} * gripper.hands) {
    return size_error("joints", r.joints.size(), std::size_t{gripper.joints} * gripper.hands);
  }
  if (r.closing_forces.size() != std::size_t{gripper.fingers} * gripper.hands) {
    return size_error("closing_forces", r.closing_forces.size(),
                      std::size_t{gripper.fingers} * gripper.hands);
  }
  if (result.trajectory) {
    if (layout.frame_slot[r.id] < 0) return which + " has a trajectory but no frame slot";
    const TrajectoryRecord& t = *result.trajectory;
    const std::size_t f = layout.frames();
    const std::size_t n3 = f * object.vertices * 3;
    if (t.object_vertices.size() != n3)
      return size_error("object_vertices", t.object_vertices.size(), n3);
    if (t.contact_forces.size() != n3)
      return size_error("contact_forces", t.contact_forces.size(), n3);
    if (t.friction_forces.size() != n3)
      return size_error("friction_forces", t.friction_forces.size(), n3);
    const std::size_t g3 = f * gripper.hands * gripper.vertices * 3;
    if (t.gripper_vertices.size() != g3)
      return size_error("gripper_vertices", t.gripper_vertices.size(), g3);
    if (t.object_poses.size() != f * 12)
      return size_error("object_poses", t.object_poses.size(), f * 12);
    const std::size_t hp = f * gripper.hands * 12;
    if (t.hand_poses.size() != hp)
      return size_error("trajectory hand_poses", t.hand_poses.size(), hp);
    const std::size_t js = f * gripper.hands * gripper.joints;
    if (t.joints.size() != js) return size_error("trajectory joints", t.joints.size(), js);
  }
  if (result.stress) {
    if (layout.stress_slot[r.id] < 0) return which + " has stress but no stress slot";
    if (result.stress->size() != object.tets) {
      return size_error("stress", result.stress->size(), object.tets);
    }
  }
  return "";
}

}  // namespace

DatasetWriter::DatasetWriter(std::filesystem::path path, DatasetLayout layout, MPI_Comm comm)
    : path_(std::move(path)), layout_(std::move(layout)), comm_(comm), rank_(comm_rank(comm)) {}

DatasetWriter::DatasetWriter(DatasetWriter&&) noexcept = default;
DatasetWriter& DatasetWriter::operator=(DatasetWriter&&) noexcept = default;

DatasetWriter::~DatasetWriter() { close(); }

void DatasetWriter::close() {
  transfer_.reset();
  file_.reset();
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
      throw DatasetError(name + ": cannot resume: " + e.what());
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

  // This rank's results in id order: a union of row hyperslabs is written in row order.
  std::vector<const CandidateResult*> sorted;
  for (const CandidateResult& result : results) sorted.push_back(&result);
  std::sort(sorted.begin(), sorted.end(),
            [](const auto* a, const auto* b) { return a->record.id < b->record.id; });
  std::vector<std::uint64_t> rows;
  for (const auto* result : sorted) rows.push_back(result->record.id);

  const hid_t file = file_;
  const hid_t transfer = transfer_;
  {
    std::vector<std::uint8_t> status, failure, trajectory_written, stress_written;
    std::vector<double> hand_poses, joints, d1, d2, displacement, closing_forces, wall_time;
    std::vector<std::uint32_t> steps, iterations, max_iterations;
    for (const auto* result : sorted) {
      const CandidateRecord& r = result->record;
      const DatasetLayout::Gripper& gripper = layout_.grippers[layout_.gripper[r.id]];
      status.push_back(static_cast<std::uint8_t>(r.status));
      failure.push_back(static_cast<std::uint8_t>(r.failure));
      pad_hands(hand_poses, r.hand_poses, gripper.hands, 12, layout_.max_hands, 12);
      pad_hands(joints, r.joints, gripper.hands, gripper.joints, layout_.max_hands,
                layout_.max_joints);
      pad_hands(closing_forces, r.closing_forces, gripper.hands, gripper.fingers, layout_.max_hands,
                layout_.max_fingers);
      d1.push_back(r.d1);
      d2.push_back(r.d2);
      pad_row(displacement, {r.displacement.begin(), r.displacement.end()}, 6);
      steps.push_back(r.newton.steps);
      iterations.push_back(r.newton.iterations);
      max_iterations.push_back(r.newton.max_iterations);
      wall_time.push_back(r.wall_time);
      trajectory_written.push_back(result->trajectory ? 1 : 0);
      stress_written.push_back(result->stress ? 1 : 0);
    }
    const h5::Handle status_memory = status_type(false);
    const h5::Handle failure_memory = failure_kind_type(false);
    write_rows(file, "/candidates/status", rows, status_memory, status.data(), transfer);
    write_rows(file, "/candidates/failure", rows, failure_memory, failure.data(), transfer);
    write_rows(file, "/candidates/hand_poses", rows, H5T_NATIVE_DOUBLE, hand_poses.data(),
               transfer);
    write_rows(file, "/candidates/joints", rows, H5T_NATIVE_DOUBLE, joints.data(), transfer);
    write_rows(file, "/candidates/d1", rows, H5T_NATIVE_DOUBLE, d1.data(), transfer);
    write_rows(file, "/candidates/d2", rows, H5T_NATIVE_DOUBLE, d2.data(), transfer);
    write_rows(file, "/candidates/displacement", rows, H5T_NATIVE_DOUBLE, displacement.data(),
               transfer);
    write_rows(file, "/candidates/closing_forces", rows, H5T_NATIVE_DOUBLE, closing_forces.data(),
               transfer);
    write_rows(file, "/candidates/newton_steps", rows, H5T_NATIVE_UINT32, steps.data(), transfer);
    write_rows(file, "/candidates/newton_iterations", rows, H5T_NATIVE_UINT32, iterations.data(),
               transfer);
    write_rows(file, "/candidates/newton_max_iterations", rows, H5T_NATIVE_UINT32,
               max_iterations.data(), transfer);
    write_rows(file, "/candidates/wall_time", rows, H5T_NATIVE_DOUBLE, wall_time.data(), transfer);
    write_rows(file, "/candidates/trajectory_written", rows, H5T_NATIVE_UINT8,
               trajectory_written.data(), transfer);
    write_rows(file, "/candidates/stress_written", rows, H5T_NATIVE_UINT8, stress_written.data(),
               transfer);
  }

  // Trajectories and stress live in per-object datasets: every rank joins the writes of every
  // dataset that any rank touches in this batch, in the same order.
  const std::size_t pairs = layout_.trajectory_slots.size();
  std::vector<std::uint8_t> touched(pairs + layout_.objects.size(), 0);
  for (const auto* result : sorted) {
    const std::uint64_t id = result->record.id;
    if (result->trajectory) touched[layout_.pair(layout_.object[id], layout_.gripper[id])] = 1;
    if (result->stress) touched[pairs + layout_.object[id]] = 1;
  }
  MPI_Allreduce(MPI_IN_PLACE, touched.data(), static_cast<int>(touched.size()), MPI_UINT8_T,
                MPI_MAX, comm_);
  const std::uint32_t gripper_count = static_cast<std::uint32_t>(layout_.grippers.size());
  for (std::size_t p = 0; p < pairs; ++p) {
    if (!touched[p]) continue;
    const auto o = static_cast<std::uint32_t>(p / gripper_count);
    const auto g = static_cast<std::uint32_t>(p % gripper_count);
    std::vector<std::uint64_t> slots;
    std::vector<const TrajectoryRecord*> trajectories;
    for (const auto* result : sorted) {
      const std::uint64_t id = result->record.id;
      if (result->trajectory && layout_.pair(layout_.object[id], layout_.gripper[id]) == p) {
        slots.push_back(static_cast<std::uint64_t>(layout_.frame_slot[id]));
        trajectories.push_back(&*result->trajectory);
      }
    }
    const std::string group = trajectory_group(o, g) + "/";
    const auto gather = [&](auto member) {
      using Value =
          typename std::remove_reference_t<decltype(trajectories[0]->*member)>::value_type;
      std::vector<Value> packed;
      for (const auto* t : trajectories) {
        packed.insert(packed.end(), (t->*member).begin(), (t->*member).end());
      }
      return packed;
    };
    write_rows(file, group + "object_vertices", slots, H5T_NATIVE_FLOAT,
               gather(&TrajectoryRecord::object_vertices).data(), transfer);
    write_rows(file, group + "gripper_vertices", slots, H5T_NATIVE_FLOAT,
               gather(&TrajectoryRecord::gripper_vertices).data(), transfer);
    write_rows(file, group + "contact_forces", slots, H5T_NATIVE_FLOAT,
               gather(&TrajectoryRecord::contact_forces).data(), transfer);
    write_rows(file, group + "friction_forces", slots, H5T_NATIVE_FLOAT,
               gather(&TrajectoryRecord::friction_forces).data(), transfer);
    write_rows(file, group + "object_poses", slots, H5T_NATIVE_DOUBLE,
               gather(&TrajectoryRecord::object_poses).data(), transfer);
    write_rows(file, group + "hand_poses", slots, H5T_NATIVE_DOUBLE,
               gather(&TrajectoryRecord::hand_poses).data(), transfer);
    write_rows(file, group + "joints", slots, H5T_NATIVE_DOUBLE,
               gather(&TrajectoryRecord::joints).data(), transfer);
  }
  for (std::uint32_t o = 0; o < layout_.objects.size(); ++o) {
    if (!touched[pairs + o]) continue;
    std::vector<std::uint64_t> slots;
    std::vector<float> packed;
    for (const auto* result : sorted) {
      const std::uint64_t id = result->record.id;
      if (result->stress && layout_.object[id] == o) {
        slots.push_back(static_cast<std::uint64_t>(layout_.stress_slot[id]));
        packed.insert(packed.end(), result->stress->begin(), result->stress->end());
      }
    }
    write_rows(file, stress_dataset(o), slots, H5T_NATIVE_FLOAT, packed.data(), transfer);
  }

  // Commit: rows reach the disk before their done flags, the flags before the journal line.
  h5::check(H5Fflush(file, H5F_SCOPE_GLOBAL), path_.string() + ": flushing a batch");
  const std::vector<std::uint8_t> ones(rows.size(), 1);
  write_rows(file, "/candidates/done", rows, H5T_NATIVE_UINT8, ones.data(), transfer);
  h5::check(H5Fflush(file, H5F_SCOPE_GLOBAL), path_.string() + ": flushing done flags");
  agree(comm_, [&] {
    if (rank_ == 0) journal_->append(all);
  });
  for (const std::uint64_t id : all) done_[id] = 1;
}

}  // namespace grip::io
