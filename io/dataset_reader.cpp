#include "io/dataset_reader.hpp"

#include <algorithm>

#include "io/dataset_error.hpp"
#include "io/enum_types.hpp"

namespace grip::io {

namespace {

h5::Handle open_dataset(hid_t file, const std::string& path) {
  return h5::dataset_handle(H5Dopen2(file, path.c_str(), H5P_DEFAULT), "opening " + path);
}

template <typename T>
std::vector<T> read_column(hid_t file, const std::string& path, hid_t memory_type) {
  return h5::read_all<T>(open_dataset(file, path), memory_type);
}

// Reads row `row` of a dataset whose first dimension indexes rows.
template <typename T>
std::vector<T> read_row(hid_t file, const std::string& path, std::uint64_t row, hid_t memory_type) {
  const h5::Handle dataset = open_dataset(file, path);
  std::vector<hsize_t> count = h5::dims(dataset);
  std::vector<hsize_t> start(count.size(), 0);
  start[0] = row;
  count[0] = 1;
  hsize_t size = 1;
  for (const hsize_t d : count) size *= d;
  std::vector<T> values(size);
  if (size == 0) return values;
  const h5::Handle file_space = h5::space_handle(H5Dget_space(dataset), "selecting a row");
  h5::check(
      H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr),
      "selecting row " + std::to_string(row) + " of " + path);
  const h5::Handle memory_space =
      h5::space_handle(H5Screate_simple(1, &size, nullptr), "shaping a row");
  h5::check(H5Dread(dataset, memory_type, memory_space, file_space, H5P_DEFAULT, values.data()),
            "reading row " + std::to_string(row) + " of " + path);
  return values;
}

// The first `hands` hands of a [max_hands][width] row, each cut to `per_hand` values.
std::vector<double> unpad_hands(const double* row, std::uint32_t hands, std::size_t per_hand,
                                std::size_t width) {
  std::vector<double> values;
  for (std::uint32_t h = 0; h < hands; ++h) {
    values.insert(values.end(), row + h * width, row + h * width + per_hand);
  }
  return values;
}

}  // namespace

DatasetReader::DatasetReader(const std::filesystem::path& path) : path_(path) {
  h5::silence_errors();
  const std::string name = path.string();
  if (!std::filesystem::exists(path)) throw DatasetError(name + ": no such file");
  if (H5Fis_hdf5(name.c_str()) <= 0) {
    throw DatasetError(name + ": not an HDF5 file, so not a grip dataset");
  }
  file_ = h5::file_handle(H5Fopen(name.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT),
                          name + ": the file is damaged or truncated");
  try {
    layout_ = DatasetLayout::read(file_);
  } catch (const DatasetError& e) {
    throw DatasetError(name + ": " + e.what());
  }
}

std::string DatasetReader::job_id() const { return h5::read_string_attribute(file_, "job_id"); }

Provenance DatasetReader::provenance() const {
  Provenance provenance;
  provenance.seed = h5::read_uint_attribute(file_, "seed");
  provenance.grip_version = h5::read_string_attribute(file_, "grip_version");
  provenance.git_revision = h5::read_string_attribute(file_, "git_revision");
  const h5::Handle group =
      h5::group_handle(H5Gopen2(file_, "/provenance", H5P_DEFAULT), "opening /provenance");
  provenance.job_file = h5::read_string_attribute(group, "job_file");
  provenance.job_text = h5::read_strings(open_dataset(file_, "/provenance/job_text")).at(0);
  const std::vector<std::string> table =
      h5::read_strings(open_dataset(file_, "/provenance/parameters"));
  for (std::size_t i = 0; i + 1 < table.size(); i += 2) {
    provenance.parameters.push_back({table[i], table[i + 1]});
  }
  return provenance;
}

ObjectRecord DatasetReader::object(std::uint32_t index) const {
  const std::string path = object_group(index);
  const h5::Handle group =
      h5::group_handle(H5Gopen2(file_, path.c_str(), H5P_DEFAULT), "opening " + path);
  ObjectRecord object;
  object.name = h5::read_string_attribute(group, "name");
  object.category = h5::read_string_attribute(group, "category");
  object.scale = h5::read_double_attribute(group, "scale");
  object.soft = h5::read_uint_attribute(group, "soft") != 0;
  object.material.young_modulus = h5::read_double_attribute(group, "young_modulus");
  object.material.poisson_ratio = h5::read_double_attribute(group, "poisson_ratio");
  object.material.density = h5::read_double_attribute(group, "density");
  object.material.friction = h5::read_double_attribute(group, "friction");
  object.vertices = read_column<double>(file_, path + "/vertices", H5T_NATIVE_DOUBLE);
  object.triangles = read_column<std::int32_t>(file_, path + "/triangles", H5T_NATIVE_INT32);
  object.tets = read_column<std::int32_t>(file_, path + "/tets", H5T_NATIVE_INT32);
  return object;
}

GripperRecord DatasetReader::gripper(std::uint32_t index) const {
  const std::string path = gripper_group(index);
  const h5::Handle group =
      h5::group_handle(H5Gopen2(file_, path.c_str(), H5P_DEFAULT), "opening " + path);
  GripperRecord gripper;
  gripper.name = h5::read_string_attribute(group, "name");
  gripper.kind = h5::read_string_attribute(group, "kind");
  gripper.soft = h5::read_uint_attribute(group, "soft") != 0;
  gripper.hands = static_cast<std::uint32_t>(h5::read_uint_attribute(group, "hands"));
  gripper.joint_names = h5::read_strings(open_dataset(file_, path + "/joint_names"));
  gripper.finger_names = h5::read_strings(open_dataset(file_, path + "/finger_names"));
  gripper.vertices = read_column<double>(file_, path + "/vertices", H5T_NATIVE_DOUBLE);
  gripper.triangles = read_column<std::int32_t>(file_, path + "/triangles", H5T_NATIVE_INT32);
  return gripper;
}

std::vector<std::uint8_t> DatasetReader::done() const {
  return read_column<std::uint8_t>(file_, "/candidates/done", H5T_NATIVE_UINT8);
}

std::vector<CandidateRecord> DatasetReader::candidates() const {
  const std::string table = "/candidates/";
  const h5::Handle status_memory = status_type(false);
  const h5::Handle failure_memory = failure_kind_type(false);
  const auto status = read_column<std::uint8_t>(file_, table + "status", status_memory);
  const auto failure = read_column<std::uint8_t>(file_, table + "failure", failure_memory);
  const auto hand_poses = read_column<double>(file_, table + "hand_poses", H5T_NATIVE_DOUBLE);
  const auto joints = read_column<double>(file_, table + "joints", H5T_NATIVE_DOUBLE);
  const auto d1 = read_column<double>(file_, table + "d1", H5T_NATIVE_DOUBLE);
  const auto d2 = read_column<double>(file_, table + "d2", H5T_NATIVE_DOUBLE);
  const auto displacement = read_column<double>(file_, table + "displacement", H5T_NATIVE_DOUBLE);
  const auto closing = read_column<double>(file_, table + "closing_forces", H5T_NATIVE_DOUBLE);
  const auto steps = read_column<std::uint32_t>(file_, table + "newton_steps", H5T_NATIVE_UINT32);
  const auto iterations =
      read_column<std::uint32_t>(file_, table + "newton_iterations", H5T_NATIVE_UINT32);
  const auto max_iterations =
      read_column<std::uint32_t>(file_, table + "newton_max_iterations", H5T_NATIVE_UINT32);
  const auto wall_time = read_column<double>(file_, table + "wall_time", H5T_NATIVE_DOUBLE);

  const std::size_t hands = layout_.max_hands;
  std::vector<CandidateRecord> records(layout_.candidate_count);
  for (std::size_t id = 0; id < records.size(); ++id) {
    const DatasetLayout::Gripper& gripper = layout_.grippers[layout_.gripper[id]];
    CandidateRecord& r = records[id];
    r.id = id;
    r.hand_poses = unpad_hands(&hand_poses[id * hands * 12], gripper.hands, 12, 12);
    r.joints = unpad_hands(&joints[id * hands * layout_.max_joints], gripper.hands, gripper.joints,
                           layout_.max_joints);
    r.closing_forces = unpad_hands(&closing[id * hands * layout_.max_fingers], gripper.hands,
                                   gripper.fingers, layout_.max_fingers);
    r.status = static_cast<Status>(status[id]);
    r.failure = static_cast<FailureKind>(failure[id]);
    r.d1 = d1[id];
    r.d2 = d2[id];
    std::copy_n(&displacement[id * 6], 6, r.displacement.begin());
    r.newton = {steps[id], iterations[id], max_iterations[id]};
    r.wall_time = wall_time[id];
  }
  return records;
}

bool DatasetReader::committed(std::uint64_t id, const char* written_column) const {
  // A flag alone is not enough: an interrupted batch may have set it before its done flag.
  return read_row<std::uint8_t>(file_, "/candidates/done", id, H5T_NATIVE_UINT8)[0] != 0 &&
         read_row<std::uint8_t>(file_, std::string("/candidates/") + written_column, id,
                                H5T_NATIVE_UINT8)[0] != 0;
}

std::optional<TrajectoryRecord> DatasetReader::trajectory(std::uint64_t id) const {
  if (id >= layout_.candidate_count) {
    throw DatasetError(path_.string() + ": no candidate " + std::to_string(id));
  }
  if (!committed(id, "trajectory_written")) return std::nullopt;
  const auto slot = static_cast<std::uint64_t>(layout_.frame_slot[id]);
  const std::string group = trajectory_group(layout_.object[id], layout_.gripper[id]) + "/";
  TrajectoryRecord t;
  t.object_vertices = read_row<float>(file_, group + "object_vertices", slot, H5T_NATIVE_FLOAT);
  t.gripper_vertices = read_row<float>(file_, group + "gripper_vertices", slot, H5T_NATIVE_FLOAT);
  t.contact_forces = read_row<float>(file_, group + "contact_forces", slot, H5T_NATIVE_FLOAT);
  t.friction_forces = read_row<float>(file_, group + "friction_forces", slot, H5T_NATIVE_FLOAT);
  t.object_poses = read_row<double>(file_, group + "object_poses", slot, H5T_NATIVE_DOUBLE);
  t.hand_poses = read_row<double>(file_, group + "hand_poses", slot, H5T_NATIVE_DOUBLE);
  t.joints = read_row<double>(file_, group + "joints", slot, H5T_NATIVE_DOUBLE);
  return t;
}

std::optional<std::vector<float>> DatasetReader::stress(std::uint64_t id) const {
  if (id >= layout_.candidate_count) {
    throw DatasetError(path_.string() + ": no candidate " + std::to_string(id));
  }
  if (!committed(id, "stress_written")) return std::nullopt;
  return read_row<float>(file_, stress_dataset(layout_.object[id]),
                         static_cast<std::uint64_t>(layout_.stress_slot[id]), H5T_NATIVE_FLOAT);
}

}  // namespace grip::io
