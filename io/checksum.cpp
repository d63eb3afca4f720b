#include "io/checksum.hpp"

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <type_traits>
#include <variant>
#include <vector>

#include "io/dataset_error.hpp"
#include "io/hdf5.hpp"

namespace grip::io {

// The checksums are over the stored (little-endian) bytes, which are the memory bytes here.
static_assert(std::endian::native == std::endian::little,
              "dataset checksums assume a little-endian host");

std::uint32_t crc32(const void* data, std::size_t bytes) {
  uLong crc = ::crc32_z(0L, Z_NULL, 0);
  const auto* next = static_cast<const Bytef*>(data);
  crc = ::crc32_z(crc, next, bytes);
  return static_cast<std::uint32_t>(crc);
}

std::uint32_t row_checksum(const Values& values, std::size_t offset, std::size_t count) {
  return std::visit(
      [&](const auto& v) -> std::uint32_t {
        using T = typename std::remove_cvref_t<decltype(v)>::value_type;
        if constexpr (std::is_arithmetic_v<T>) {
          return crc32(v.data() + offset, count * sizeof(T));
        } else {
          throw DatasetError("rows of strings have no checksum");
        }
      },
      values);
}

std::uint32_t whole_checksum(const Values& values, std::size_t string_width) {
  if (const auto* strings = std::get_if<std::vector<std::string>>(&values)) {
    const std::vector<char> packed = packed_strings(*strings, string_width);
    return crc32(packed.data(), packed.size());
  }
  return row_checksum(values, 0, value_count(values));
}

void write_whole_checksum(hid_t dataset, const Values& values, std::size_t string_width) {
  h5::write_attribute(dataset, kChecksumAttribute,
                      std::uint64_t{whole_checksum(values, string_width)});
}

WholeChecksums whole_checksums(hid_t dataset, const std::string& path, const Values& values) {
  std::size_t width = 1;
  if (std::holds_alternative<std::vector<std::string>>(values)) {
    const h5::Handle type = h5::type_handle(H5Dget_type(dataset), "reading the type of " + path);
    width = H5Tget_size(type);
  }
  if (H5Aexists(dataset, kChecksumAttribute) <= 0) {
    throw DatasetError(path + " has no checksum attribute; the file is damaged");
  }
  return {h5::read_uint_attribute(dataset, kChecksumAttribute), whole_checksum(values, width)};
}

void verify_whole_checksum(hid_t dataset, const std::string& path, const Values& values) {
  const WholeChecksums checksums = whole_checksums(dataset, path, values);
  if (!checksums.match()) {
    throw DatasetError(path + " does not match the checksum written when the dataset was created " +
                       "(stored " + std::to_string(checksums.stored) + ", computed " +
                       std::to_string(checksums.computed) + "); the file is damaged");
  }
}

}  // namespace grip::io
