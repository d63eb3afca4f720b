#include "io/layout_writer.hpp"

#include <array>
#include <cstddef>
#include <string>

#include "io/checksum.hpp"
#include "io/column.hpp"
#include "io/column_values.hpp"
#include "io/dataset_columns.hpp"
#include "io/dataset_error.hpp"
#include "io/hdf5.hpp"

namespace grip::io {

namespace {

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

// Writes a whole dataset from rank 0; the other ranks join the collective call with nothing.
void write_from_root(hid_t dataset, hid_t memory_type, const void* data, int rank, hid_t transfer) {
  if (h5::element_count(h5::dims(dataset)) == 0) return;  // same on every rank
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

void write_gripper(hid_t file, std::uint32_t index, const GripperRecord& gripper,
                   const DatasetLayout& layout, int rank, hid_t transfer) {
  const h5::Handle group = make_group(file, gripper_group(index));
  h5::write_attribute(group, "name", gripper.name);
  h5::write_attribute(group, "kind", gripper.kind);
  h5::write_attribute(group, "soft", std::uint64_t{gripper.soft});
  h5::write_attribute(group, "hands", std::uint64_t{gripper.hands});
  for (const Column& column : dataset_columns()) {
    if (column.place == Place::kGripper) {
      create_record_column(group, column, gripper, rank, transfer);
    } else if (column.place == Place::kFingerStress && layout.grippers[index].stress_slots > 0) {
      Sizes sizes = Sizes::of(layout);
      sizes.gripper = layout.grippers[index];
      create_row_column(group, column, sizes.gripper.stress_slots, sizes, nullptr, rank, transfer);
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

// The checksum creation wrote for `values` in `location`'s dataset `column`, against theirs;
// false where they differ.
bool stored_checksum_matches(hid_t location, const Column& column, const Values& values,
                             const std::string& path) {
  const h5::Handle dataset =
      h5::dataset_handle(H5Dopen2(location, column.name, H5P_DEFAULT), "opening " + path);
  // Strings longer than the stored width would be cut to it, and could match.
  if (column.element == Element::kString) {
    const h5::Handle type = h5::type_handle(H5Dget_type(dataset), "reading the type of " + path);
    if (H5Tget_size(type) != string_width(std::get<std::vector<std::string>>(values))) {
      return false;
    }
  }
  return whole_checksums(dataset, path, values).match();
}

template <typename Record>
bool record_matches(hid_t group, Place place, const Record& record, const std::string& prefix,
                    std::string& differing) {
  for (const Column& column : dataset_columns()) {
    if (column.place != place) continue;
    Values values = empty_values(value_index(column.element));
    column.access_to<Record>().get(record, values);
    const std::string path = prefix + "/" + column.name;
    if (!stored_checksum_matches(group, column, values, path)) {
      differing = path;
      return false;
    }
  }
  return true;
}

}  // namespace

void write_layout(hid_t file, const DatasetPlan& plan, const DatasetLayout& layout,
                  const Provenance& provenance, int rank) {
  const h5::Handle transfer = h5::transfer_properties(true);
  write_provenance(file, provenance, layout, plan.objects.size(), plan.grippers.size(), rank,
                   transfer);
  make_group(file, "/objects");
  for (std::uint32_t o = 0; o < plan.objects.size(); ++o) {
    write_object(file, o, plan.objects[o], layout, plan.grippers.size(), rank, transfer);
  }
  make_group(file, "/grippers");
  for (std::uint32_t g = 0; g < plan.grippers.size(); ++g) {
    write_gripper(file, g, plan.grippers[g], layout, rank, transfer);
  }
  write_candidate_table(file, layout, rank, transfer);
}

void check_layout(hid_t file, const std::string& name, const DatasetPlan& plan,
                  const DatasetLayout& layout) {
  const std::string advice =
      "; nothing was changed. The grip that made the dataset plans this job otherwise (another "
      "version, or one that meshed or synthesized differently): finish it with that grip, or "
      "start a new dataset";
  if (plan.objects.size() != layout.objects.size() ||
      plan.grippers.size() != layout.grippers.size()) {
    throw DatasetError(name + ": the job plans " + std::to_string(plan.objects.size()) +
                       " objects and " + std::to_string(plan.grippers.size()) +
                       " grippers, the dataset holds " + std::to_string(layout.objects.size()) +
                       " and " + std::to_string(layout.grippers.size()) + advice);
  }
  std::string differing;
  // Each record of `records` against its group (`group_of` its index), named `kind` in errors.
  const auto check_records = [&](const auto& records, Place place, auto group_of,
                                 const char* kind) {
    for (std::uint32_t i = 0; i < records.size(); ++i) {
      const std::string path = group_of(i);
      const h5::Handle group =
          h5::group_handle(H5Gopen2(file, path.c_str(), H5P_DEFAULT), name + ": opening " + path);
      if (!record_matches(group, place, records[i], path, differing)) {
        throw DatasetError(name + ": " + kind + " '" + records[i].name + "' (" + differing +
                           ") is not the one the dataset holds" + advice);
      }
    }
  };
  check_records(plan.objects, Place::kObject, object_group, "object");
  check_records(plan.grippers, Place::kGripper, gripper_group, "gripper");
  const DatasetLayout planned = DatasetLayout::from_plan(plan);
  const h5::Handle table =
      h5::group_handle(H5Gopen2(file, "/candidates", H5P_DEFAULT), name + ": opening /candidates");
  if (planned.candidate_count != layout.candidate_count ||
      !record_matches(table, Place::kPlan, planned, "/candidates", differing)) {
    throw DatasetError(
        name + ": the job plans other candidates (" + std::to_string(planned.candidate_count) +
        ", their slots in " + (differing.empty() ? std::string("/candidates") : differing) +
        ") than the dataset holds (" + std::to_string(layout.candidate_count) + ")" + advice);
  }
}

}  // namespace grip::io
