#pragma once
// Where an HDF5 file keeps its stored values: the byte ranges of every dataset's contiguous
// storage, in file order. Every other byte is HDF5's own structure (superblock, object headers
// with their attributes, B-trees, heaps). A grip dataset stores every dataset contiguously and
// allocates it at creation (io/layout_writer.cpp), so its values are all in these ranges.
#include <hdf5.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <vector>

namespace grip::fuzz {

struct StorageRange {
  std::uint64_t offset = 0;
  std::uint64_t size = 0;
};

inline std::vector<StorageRange> storage_ranges(const std::filesystem::path& file) {
  const hid_t id = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (id < 0) throw std::runtime_error(file.string() + ": cannot open it with HDF5");
  std::vector<StorageRange> ranges;
  const auto visit = [](hid_t group, const char* name, const H5L_info_t*, void* out) -> herr_t {
    const hid_t object = H5Oopen(group, name, H5P_DEFAULT);
    if (object < 0) return -1;
    if (H5Iget_type(object) == H5I_DATASET) {
      const haddr_t offset = H5Dget_offset(object);
      const hsize_t size = H5Dget_storage_size(object);
      // An empty dataset has no storage (HADDR_UNDEF) and nothing to mutate.
      if (offset != HADDR_UNDEF && size > 0) {
        static_cast<std::vector<StorageRange>*>(out)->push_back({offset, size});
      }
    }
    H5Oclose(object);
    return 0;
  };
  const herr_t status = H5Lvisit(id, H5_INDEX_NAME, H5_ITER_INC, visit, &ranges);
  H5Fclose(id);
  if (status < 0) throw std::runtime_error(file.string() + ": cannot list its datasets");
  std::sort(ranges.begin(), ranges.end(),
            [](const StorageRange& a, const StorageRange& b) { return a.offset < b.offset; });
  return ranges;
}

// The bytes of `file` in `ranges`, one range after the other.
inline std::vector<std::uint8_t> stored_values(const std::vector<std::uint8_t>& file,
                                               const std::vector<StorageRange>& ranges) {
  std::vector<std::uint8_t> values;
  for (const StorageRange& range : ranges) {
    values.insert(values.end(), file.begin() + static_cast<std::ptrdiff_t>(range.offset),
                  file.begin() + static_cast<std::ptrdiff_t>(range.offset + range.size));
  }
  return values;
}

// `file` with its ranges filled from `values` in order, as far as `values` reaches: the rest
// keeps the file's own bytes.
inline void overwrite_values(std::vector<std::uint8_t>& file,
                             const std::vector<StorageRange>& ranges, const std::uint8_t* values,
                             std::size_t count) {
  for (const StorageRange& range : ranges) {
    if (count == 0) return;
    const std::size_t n = std::min<std::uint64_t>(range.size, count);
    std::copy(values, values + n, file.begin() + static_cast<std::ptrdiff_t>(range.offset));
    values += n;
    count -= n;
  }
}

}  // namespace grip::fuzz
