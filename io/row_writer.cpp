#include "io/row_writer.hpp"

#include <algorithm>
#include <cstddef>
#include <limits>
#include <numeric>
#include <type_traits>
#include <utility>

#include "io/checksum.hpp"
#include "io/column.hpp"
#include "io/column_values.hpp"
#include "io/dataset_columns.hpp"
#include "io/dataset_error.hpp"

namespace grip::io {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Writes one row per entry of `rows` (ascending) from `data` (rows packed in that order).
// Collectively: one call, a rank with no rows joining with an empty selection. Independently:
// one call per run of consecutive rows, each a contiguous range of the file (no read-modify-write
// of a range another rank may be writing).
void write_rows(hid_t dataset, const std::vector<std::uint64_t>& rows, hid_t memory_type,
                const void* data, hid_t transfer, bool collective) {
  if (!collective && rows.empty()) return;
  const std::vector<hsize_t> dims = h5::dims(dataset);
  const std::size_t row_size =
      h5::element_count(std::vector<hsize_t>(dims.begin() + 1, dims.end()));
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

}  // namespace

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

std::vector<std::uint8_t> touched_by(const DatasetLayout& layout,
                                     const std::vector<const CandidateResult*>& sorted) {
  const std::size_t pairs = layout.trajectory_slots.size();
  const std::size_t objects = layout.objects.size();
  std::vector<std::uint8_t> touched(pairs + objects + layout.grippers.size(), 0);
  for (const auto* result : sorted) {
    const std::uint64_t id = result->record.id;
    if (result->trajectory) touched[layout.pair(layout.object[id], layout.gripper[id])] = 1;
    if (result->stress) touched[pairs + layout.object[id]] = 1;
    if (result->finger_stress) touched[pairs + objects + layout.gripper[id]] = 1;
  }
  return touched;
}

RowWriter::RowWriter(hid_t file, const DatasetLayout& layout, std::string name)
    : name_(std::move(name)),
      collective_(h5::transfer_properties(true)),
      independent_(h5::transfer_properties(false)) {
  const auto open = [&](const std::string& path) {
    datasets_.emplace(path, h5::open_dataset(file, path));
  };
  for (const Column& column : dataset_columns()) {
    if (column.place == Place::kResult || column.place == Place::kDone ||
        column.place == Place::kChecksum) {
      open(std::string("/candidates/") + column.name);
    }
  }
  const std::uint32_t grippers = static_cast<std::uint32_t>(layout.grippers.size());
  for (std::uint32_t g = 0; g < grippers; ++g) {
    for (const Column& column : dataset_columns()) {
      if (column.place == Place::kFingerStress && layout.grippers[g].stress_slots > 0) {
        open(gripper_group(g) + "/" + column.name);
      }
    }
  }
  for (std::uint32_t o = 0; o < layout.objects.size(); ++o) {
    for (const Column& column : dataset_columns()) {
      if (column.place == Place::kStress && layout.objects[o].stress_slots > 0) {
        open(object_group(o) + "/" + column.name);
      }
    }
    for (std::uint32_t g = 0; g < grippers; ++g) {
      if (layout.trajectory_slots[layout.pair(o, g)] == 0) continue;
      for (const Column& column : dataset_columns()) {
        if (column.place == Place::kTrajectory) open(trajectory_group(o, g) + "/" + column.name);
      }
    }
  }
}

hid_t RowWriter::dataset(const std::string& path) const {
  const auto found = datasets_.find(path);
  if (found == datasets_.end()) throw DatasetError(name_ + ": no dataset " + path);
  return found->second;
}

// One write_results call: its results, how they are written, and each result's checksums (in
// `sorted` order, one entry per checksummed column), written after the rows they cover.
struct RowWriter::ResultRows {
  const RowWriter& writer;
  const DatasetLayout& layout;
  const std::vector<const CandidateResult*>& sorted;
  bool collective;
  hid_t transfer;
  std::size_t entries = checksum_entries();
  std::vector<std::uint32_t> checksums = std::vector<std::uint32_t>(sorted.size() * entries, 0);

  // Writes `values`, rows of `row_size` packed in order for the results at `positions` in
  // `sorted`, into rows `at` of the dataset at `path`, and records their checksums.
  void write(const Column& column, const std::string& path, const std::vector<std::uint64_t>& at,
             const std::vector<std::size_t>& positions, std::size_t row_size,
             const Values& values) {
    const std::size_t entry = checksum_entry(column);
    for (std::size_t i = 0; i < positions.size(); ++i) {
      checksums[positions[i] * entries + entry] = row_checksum(values, i * row_size, row_size);
    }
    const h5::Handle memory_type = element_type(column.element, false);
    write_rows(writer.dataset(path), at, memory_type, number_data(values), transfer, collective);
  }

  void write_table(const std::vector<std::uint64_t>& rows) {
    std::vector<std::size_t> all_positions(sorted.size());
    std::iota(all_positions.begin(), all_positions.end(), std::size_t{0});
    const Sizes table = Sizes::of(layout);
    for (const Column& column : dataset_columns()) {
      if (column.place != Place::kResult) continue;
      write(column, std::string("/candidates/") + column.name, rows, all_positions,
            row_size(column, table), packed_rows(column, sorted, layout));
    }
  }

  void write_trajectories(std::uint32_t o, std::uint32_t g) {
    const std::size_t p = layout.pair(o, g);
    std::vector<std::uint64_t> slots;
    std::vector<std::size_t> positions;
    std::vector<const TrajectoryRecord*> trajectories;
    for (std::size_t i = 0; i < sorted.size(); ++i) {
      const std::uint64_t id = sorted[i]->record.id;
      if (sorted[i]->trajectory && layout.pair(layout.object[id], layout.gripper[id]) == p) {
        slots.push_back(static_cast<std::uint64_t>(layout.frame_slot[id]));
        positions.push_back(i);
        trajectories.push_back(&*sorted[i]->trajectory);
      }
    }
    const std::string group = trajectory_group(o, g) + "/";
    const Sizes sizes = Sizes::of(layout, o, g);
    for (const Column& column : dataset_columns()) {
      if (column.place != Place::kTrajectory) continue;
      write(column, group + column.name, slots, positions, row_size(column, sizes),
            packed_rows(column, trajectories, layout));
    }
  }

  // The stress rows of one object (kStress) or one gripper (kFingerStress): the results that
  // `have` one there, at their `slot`s.
  template <typename Has, typename Slot>
  void write_stress(Place place, const std::string& group, const Sizes& sizes, Has have,
                    Slot slot) {
    std::vector<std::uint64_t> slots;
    std::vector<std::size_t> positions;
    std::vector<const CandidateResult*> stressed;
    for (std::size_t i = 0; i < sorted.size(); ++i) {
      if (have(*sorted[i])) {
        slots.push_back(static_cast<std::uint64_t>(slot(sorted[i]->record.id)));
        positions.push_back(i);
        stressed.push_back(sorted[i]);
      }
    }
    for (const Column& column : dataset_columns()) {
      if (column.place != place) continue;
      write(column, group + "/" + column.name, slots, positions, row_size(column, sizes),
            packed_rows(column, stressed, layout));
    }
  }

  void write_object_stress(std::uint32_t o) {
    Sizes sizes = Sizes::of(layout);
    sizes.object = layout.objects[o];
    write_stress(
        Place::kStress, object_group(o), sizes,
        [&](const CandidateResult& r) { return r.stress && layout.object[r.record.id] == o; },
        [&](std::uint64_t id) { return layout.stress_slot[id]; });
  }

  void write_finger_stress(std::uint32_t g) {
    Sizes sizes = Sizes::of(layout);
    sizes.gripper = layout.grippers[g];
    write_stress(
        Place::kFingerStress, gripper_group(g), sizes,
        [&](const CandidateResult& r) {
          return r.finger_stress && layout.gripper[r.record.id] == g;
        },
        [&](std::uint64_t id) { return layout.finger_stress_slot[id]; });
  }
};

void RowWriter::write_results(const DatasetLayout& layout,
                              const std::vector<const CandidateResult*>& sorted,
                              const std::vector<std::uint8_t>& touched, bool collective) const {
  ResultRows result_rows{*this, layout, sorted, collective,
                         collective ? collective_ : independent_};
  const std::vector<std::uint64_t> rows = ids_of(sorted);
  result_rows.write_table(rows);
  // Trajectories and stress live in per-object and per-gripper datasets, written in the same
  // order everywhere.
  const std::size_t pairs = layout.trajectory_slots.size();
  const std::uint32_t gripper_count = static_cast<std::uint32_t>(layout.grippers.size());
  for (std::size_t p = 0; p < pairs; ++p) {
    if (!touched[p]) continue;
    result_rows.write_trajectories(static_cast<std::uint32_t>(p / gripper_count),
                                   static_cast<std::uint32_t>(p % gripper_count));
  }
  for (std::uint32_t o = 0; o < layout.objects.size(); ++o) {
    if (touched[pairs + o]) result_rows.write_object_stress(o);
  }
  for (std::uint32_t g = 0; g < gripper_count; ++g) {
    if (touched[pairs + layout.objects.size() + g]) result_rows.write_finger_stress(g);
  }
  write_rows(dataset("/candidates/checksum"), rows, H5T_NATIVE_UINT32, result_rows.checksums.data(),
             result_rows.transfer, collective);
}

void RowWriter::write_done(const std::vector<std::uint64_t>& rows, bool collective) const {
  const std::vector<std::uint8_t> ones(rows.size(), 1);
  write_rows(dataset("/candidates/done"), rows, H5T_NATIVE_UINT8, ones.data(),
             collective ? collective_ : independent_, collective);
}

}  // namespace grip::io
