#pragma once
// CRC-32 checksums of what a dataset stores (zlib's CRC-32 over the values' little-endian
// bytes, as h5py's zlib.crc32 computes them): per row and column for what each commit round
// writes, per dataset for what creation writes whole. docs/dataset-format.md, "Checksums".
#include <hdf5.h>

#include <cstddef>
#include <cstdint>
#include <string>

#include "io/column.hpp"
#include "io/column_values.hpp"

namespace grip::io {

// The attribute that holds the checksum of a dataset written whole at creation.
inline constexpr const char* kChecksumAttribute = "checksum";

std::uint32_t crc32(const void* data, std::size_t bytes);

// The checksum of numbers [offset, offset + count) of `values` (a row).
std::uint32_t row_checksum(const Values& values, std::size_t offset, std::size_t count);

// The checksum of a whole dataset's values; strings as stored, NUL-padded to `string_width`.
std::uint32_t whole_checksum(const Values& values, std::size_t string_width);

// Writes the checksum attribute of a dataset created whole from `values` (collective in
// parallel HDF5: every rank passes the same values).
void write_whole_checksum(hid_t dataset, const Values& values, std::size_t string_width);

// The checksum attribute written with `dataset` when it was created, and the checksum of
// `values` in the dataset's string width; throws DatasetError when the attribute is missing.
struct WholeChecksums {
  std::uint64_t stored = 0;
  std::uint32_t computed = 0;
  bool match() const { return stored == computed; }
};
WholeChecksums whole_checksums(hid_t dataset, const std::string& path, const Values& values);

// Throws DatasetError "<path> does not match ..." when `values`, read whole from `dataset`,
// do not match its checksum attribute.
void verify_whole_checksum(hid_t dataset, const std::string& path, const Values& values);

}  // namespace grip::io
