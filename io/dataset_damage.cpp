#include "io/dataset_damage.hpp"

#include <algorithm>
#include <utility>

#include "io/checksum.hpp"
#include "io/column.hpp"
#include "io/dataset_columns.hpp"
#include "io/hdf5.hpp"

namespace grip::io {

namespace {

constexpr std::size_t kBlockBytes = std::size_t{16} << 20;

std::vector<std::uint8_t> flags(hid_t file, const std::string& path) {
  return h5::read_all<std::uint8_t>(h5::open_dataset(file, path), H5T_NATIVE_UINT8);
}

// A dataset's rows to check: (row, candidate) in row order.
using Rows = std::vector<std::pair<std::uint64_t, std::uint64_t>>;

class Checker {
 public:
  explicit Checker(hid_t file)
      : file_(file),
        entries_(checksum_entries()),
        stored_(h5::read_all<std::uint32_t>(h5::open_dataset(file, "/candidates/checksum"),
                                            H5T_NATIVE_UINT32)) {}

  // Compares `rows` of column `column` at `path` (rows of `row_size` values) with the stored
  // checksums, reading blocks of consecutive rows.
  void check(const Column& column, const std::string& path, std::size_t row_size,
             const Rows& rows) {
    if (rows.empty()) return;
    const h5::Handle dataset = h5::open_dataset(file_, path);
    const std::size_t row_bytes =
        std::max<std::size_t>(row_size * element_bytes(column.element), 1);
    const std::uint64_t per_block = std::max<std::size_t>(kBlockBytes / row_bytes, 1);
    const std::size_t entry = checksum_entry(column);
    for (std::size_t i = 0; i < rows.size();) {
      const std::uint64_t first = rows[i].first;
      const std::uint64_t last = std::min(first + per_block, rows.back().first + 1);
      const Values block = read_rows_values(dataset, path, first, last - first, column.element);
      for (; i < rows.size() && rows[i].first < last; ++i) {
        const auto [row, candidate] = rows[i];
        const std::uint32_t computed = row_checksum(block, (row - first) * row_size, row_size);
        if (computed != stored_[candidate * entries_ + entry]) {
          damage_.push_back({candidate, path, entry});
        }
      }
    }
  }

  std::vector<Damage> damage() {
    std::stable_sort(damage_.begin(), damage_.end(), [](const Found& a, const Found& b) {
      return a.candidate != b.candidate ? a.candidate < b.candidate : a.entry < b.entry;
    });
    std::vector<Damage> out;
    for (Found& found : damage_) out.push_back({found.candidate, std::move(found.dataset)});
    return out;
  }

 private:
  struct Found {
    std::uint64_t candidate;
    std::string dataset;
    std::size_t entry;
  };
  hid_t file_;
  std::size_t entries_;
  std::vector<std::uint32_t> stored_;
  std::vector<Found> damage_;
};

}  // namespace

std::vector<Damage> find_damage(hid_t file, const DatasetLayout& layout,
                                const std::vector<std::uint8_t>& check) {
  Checker checker(file);
  const std::vector<std::uint8_t> trajectory = flags(file, "/candidates/trajectory_written");
  const std::vector<std::uint8_t> stress = flags(file, "/candidates/stress_written");
  const std::vector<std::uint8_t> finger_stress = flags(file, "/candidates/finger_stress_written");
  Rows table;
  std::vector<Rows> frame_rows(layout.trajectory_slots.size());
  std::vector<Rows> stress_rows(layout.objects.size());
  std::vector<Rows> finger_stress_rows(layout.grippers.size());
  for (std::uint64_t id = 0; id < layout.candidate_count; ++id) {
    if (!check[id]) continue;
    table.emplace_back(id, id);
    const std::uint32_t o = layout.object[id];
    if (trajectory[id] && layout.frame_slot[id] >= 0) {
      frame_rows[layout.pair(o, layout.gripper[id])].emplace_back(layout.frame_slot[id], id);
    }
    if (stress[id] && layout.stress_slot[id] >= 0) {
      stress_rows[o].emplace_back(layout.stress_slot[id], id);
    }
    if (finger_stress[id] && layout.finger_stress_slot[id] >= 0) {
      finger_stress_rows[layout.gripper[id]].emplace_back(layout.finger_stress_slot[id], id);
    }
  }
  for (Rows& rows : frame_rows) std::sort(rows.begin(), rows.end());
  for (Rows& rows : stress_rows) std::sort(rows.begin(), rows.end());
  for (Rows& rows : finger_stress_rows) std::sort(rows.begin(), rows.end());

  const auto grippers = static_cast<std::uint32_t>(layout.grippers.size());
  for (const Column& column : dataset_columns()) {
    if (column.place == Place::kResult) {
      checker.check(column, std::string("/candidates/") + column.name,
                    row_size(column, Sizes::of(layout)), table);
    } else if (column.place == Place::kTrajectory) {
      for (std::size_t p = 0; p < frame_rows.size(); ++p) {
        const auto o = static_cast<std::uint32_t>(p / grippers);
        const auto g = static_cast<std::uint32_t>(p % grippers);
        checker.check(column, trajectory_group(o, g) + "/" + column.name,
                      row_size(column, Sizes::of(layout, o, g)), frame_rows[p]);
      }
    } else if (column.place == Place::kStress) {
      for (std::uint32_t o = 0; o < stress_rows.size(); ++o) {
        Sizes sizes = Sizes::of(layout);
        sizes.object = layout.objects[o];
        checker.check(column, object_group(o) + "/" + column.name, row_size(column, sizes),
                      stress_rows[o]);
      }
    } else if (column.place == Place::kFingerStress) {
      for (std::uint32_t g = 0; g < finger_stress_rows.size(); ++g) {
        Sizes sizes = Sizes::of(layout);
        sizes.gripper = layout.grippers[g];
        checker.check(column, gripper_group(g) + "/" + column.name, row_size(column, sizes),
                      finger_stress_rows[g]);
      }
    }
  }
  return checker.damage();
}

}  // namespace grip::io
