#include "io/dataset_reader.hpp"

#include <utility>

#include "io/checksum.hpp"
#include "io/column.hpp"
#include "io/dataset_columns.hpp"
#include "io/dataset_error.hpp"

namespace grip::io {

namespace {

template <typename T>
std::vector<T> read_column(hid_t file, const std::string& path, hid_t memory_type) {
  return h5::read_all<T>(h5::open_dataset(file, path), memory_type);
}

// Puts the whole-record columns of `place` under `group` into `record`, each checked against
// the checksum written at creation (DatasetError naming `name`, the file, if one differs).
template <typename Record>
void read_record(hid_t file, const std::string& name, const std::string& group, Place place,
                 Record& record) {
  for (const Column& column : dataset_columns()) {
    if (column.place != place) continue;
    const std::string path = group + "/" + column.name;
    const h5::Handle dataset = h5::open_dataset(file, path);
    const Values values = read_values(dataset, column.element);
    try {
      verify_whole_checksum(dataset, path, values);
    } catch (const DatasetError& e) {
      throw DatasetError(name + ": " + e.what());
    }
    column.access_to<Record>().put(values, record);
  }
}

// Puts row `row` of the columns of `place` under `group` into `record`.
template <typename Record>
void read_record_row(hid_t file, const std::string& group, Place place, std::uint64_t row,
                     Record& record) {
  for (const Column& column : dataset_columns()) {
    if (column.place != place) continue;
    const std::string path = group + "/" + column.name;
    column.access_to<Record>().put(
        read_row_values(h5::open_dataset(file, path), path, row, column.element), record);
  }
}

}  // namespace

DatasetReader::DatasetReader(const std::filesystem::path& path) : path_(path) {
  h5::silence_errors();
  const std::string name = path.string();
  if (!std::filesystem::exists(path)) throw DatasetError(name + ": no such file");
  if (std::filesystem::is_directory(path))
    throw DatasetError(name + ": is a directory, not a dataset");
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
  read_record(file_, path_.string(), "/provenance", Place::kProvenance, provenance);
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
  read_record(file_, path_.string(), path, Place::kObject, object);
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
  read_record(file_, path_.string(), path, Place::kGripper, gripper);
  return gripper;
}

std::vector<std::uint8_t> DatasetReader::done() const {
  return read_column<std::uint8_t>(file_, "/candidates/done", H5T_NATIVE_UINT8);
}

std::vector<Damage> DatasetReader::damage() const {
  try {
    return find_damage(file_, layout_, done());
  } catch (const DatasetError& e) {
    throw DatasetError(path_.string() + ": " + e.what());
  }
}

std::vector<CandidateRecord> DatasetReader::candidates() const {
  std::vector<CandidateResult> results(layout_.candidate_count);
  for (std::size_t id = 0; id < results.size(); ++id) results[id].record.id = id;
  const Sizes table = Sizes::of(layout_);
  for (const Column& column : dataset_columns()) {
    if (column.place != Place::kResult) continue;
    const Access<CandidateResult>& access = column.access_to<CandidateResult>();
    if (access.put == nullptr) continue;  // the written flags, read by committed()
    const Values values = read_values(
        h5::open_dataset(file_, std::string("/candidates/") + column.name), column.element);
    const std::size_t width = row_size(column, table);
    for (std::size_t id = 0; id < results.size(); ++id) {
      Values row = slice(values, id * width, width);
      if (column.per_hand != nullptr) {
        const DatasetLayout::Gripper& gripper = layout_.grippers[layout_.gripper[id]];
        row = unpadded(row, gripper.hands, column.per_hand(gripper), width / table.max_hands);
      }
      access.put(row, results[id]);
    }
  }
  std::vector<CandidateRecord> records;
  records.reserve(results.size());
  for (CandidateResult& result : results) records.push_back(std::move(result.record));
  return records;
}

bool DatasetReader::committed(std::uint64_t id, const char* written_column) const {
  // A flag alone is not enough: an interrupted batch may have set it before its done flag.
  const auto flag = [&](const std::string& path) {
    const Values row = read_row_values(h5::open_dataset(file_, path), path, id, Element::kUint8);
    return std::get<std::vector<std::uint8_t>>(row).at(0) != 0;
  };
  return flag("/candidates/done") && flag(std::string("/candidates/") + written_column);
}

bool DatasetReader::has_trajectory(std::uint64_t id) const {
  if (id >= layout_.candidate_count) {
    throw DatasetError(path_.string() + ": no candidate " + std::to_string(id));
  }
  return committed(id, "trajectory_written");
}

std::optional<TrajectoryRecord> DatasetReader::trajectory(std::uint64_t id) const {
  if (id >= layout_.candidate_count) {
    throw DatasetError(path_.string() + ": no candidate " + std::to_string(id));
  }
  if (!committed(id, "trajectory_written")) return std::nullopt;
  TrajectoryRecord trajectory;
  read_record_row(file_, trajectory_group(layout_.object[id], layout_.gripper[id]),
                  Place::kTrajectory, static_cast<std::uint64_t>(layout_.frame_slot[id]),
                  trajectory);
  return trajectory;
}

std::optional<std::vector<float>> DatasetReader::stress(std::uint64_t id) const {
  if (id >= layout_.candidate_count) {
    throw DatasetError(path_.string() + ": no candidate " + std::to_string(id));
  }
  if (!committed(id, "stress_written")) return std::nullopt;
  CandidateResult result;
  read_record_row(file_, object_group(layout_.object[id]), Place::kStress,
                  static_cast<std::uint64_t>(layout_.stress_slot[id]), result);
  return std::move(result.stress);
}

std::optional<std::vector<float>> DatasetReader::finger_stress(std::uint64_t id) const {
  if (id >= layout_.candidate_count) {
    throw DatasetError(path_.string() + ": no candidate " + std::to_string(id));
  }
  if (!committed(id, "finger_stress_written")) return std::nullopt;
  CandidateResult result;
  read_record_row(file_, gripper_group(layout_.gripper[id]), Place::kFingerStress,
                  static_cast<std::uint64_t>(layout_.finger_stress_slot[id]), result);
  return std::move(result.finger_stress);
}

}  // namespace grip::io
