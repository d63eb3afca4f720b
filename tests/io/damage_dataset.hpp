#pragma once
// Damage for the dataset tests, done as a stray program would do it: HDF5 API writes into a
// closed dataset file (serial HDF5) that set a stored index out of range, flip a byte of a
// stored value, change an attribute or replace a dataset with one of another shape.
#include <hdf5.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace grip::io::testing {

namespace damage_detail {

inline void check(herr_t status, const std::string& what) {
  if (status < 0) throw std::runtime_error("damaging a dataset: " + what);
}

// The file opened for writing, closed (and flushed) when it goes.
class OpenFile {
 public:
  explicit OpenFile(const std::filesystem::path& path)
      : id_(H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT)) {
    check(id_ < 0 ? -1 : 0, "opening " + path.string());
  }
  ~OpenFile() { H5Fclose(id_); }
  OpenFile(const OpenFile&) = delete;
  OpenFile& operator=(const OpenFile&) = delete;
  hid_t get() const { return id_; }

 private:
  hid_t id_;
};

template <typename T>
hid_t native_type() {
  if constexpr (std::is_same_v<T, std::uint32_t>) return H5T_NATIVE_UINT32;
  if constexpr (std::is_same_v<T, std::int64_t>) return H5T_NATIVE_INT64;
  if constexpr (std::is_same_v<T, double>) return H5T_NATIVE_DOUBLE;
  if constexpr (std::is_same_v<T, float>) return H5T_NATIVE_FLOAT;
}

// Reads a whole dataset in `type`, lets `change` edit its bytes, writes it back.
template <typename Change>
void rewrite(const std::filesystem::path& file, const std::string& path, hid_t type,
             Change&& change) {
  const OpenFile open(file);
  const hid_t dataset = H5Dopen2(open.get(), path.c_str(), H5P_DEFAULT);
  check(dataset < 0 ? -1 : 0, "opening " + path);
  const hid_t space = H5Dget_space(dataset);
  const auto elements = static_cast<std::size_t>(H5Sget_simple_extent_npoints(space));
  H5Sclose(space);
  std::vector<unsigned char> bytes(elements * H5Tget_size(type));
  check(H5Dread(dataset, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data()), "reading " + path);
  change(bytes);
  check(H5Dwrite(dataset, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data()), "writing " + path);
  H5Dclose(dataset);
}

}  // namespace damage_detail

// Sets element `index` (row-major over the whole dataset) of the dataset at `path` to `value`.
template <typename T>
void set_element(const std::filesystem::path& file, const std::string& path, std::size_t index,
                 T value) {
  damage_detail::rewrite(file, path, damage_detail::native_type<T>(),
                         [&](std::vector<unsigned char>& bytes) {
                           std::memcpy(bytes.data() + index * sizeof(T), &value, sizeof(T));
                         });
}

// Flips the lowest bit of byte `byte` of the values of the dataset at `path` (their bytes in
// row-major order, as stored).
inline void flip_byte(const std::filesystem::path& file, const std::string& path,
                      std::size_t byte) {
  const damage_detail::OpenFile open(file);
  const hid_t dataset = H5Dopen2(open.get(), path.c_str(), H5P_DEFAULT);
  damage_detail::check(dataset < 0 ? -1 : 0, "opening " + path);
  const hid_t stored = H5Dget_type(dataset);
  const hid_t type = H5Tget_native_type(stored, H5T_DIR_ASCEND);
  H5Tclose(stored);
  H5Dclose(dataset);
  damage_detail::rewrite(file, path, type,
                         [&](std::vector<unsigned char>& bytes) { bytes.at(byte) ^= 1u; });
  H5Tclose(type);
}

// Sets the uint64 attribute `name` of the group or dataset at `object`.
inline void set_attribute(const std::filesystem::path& file, const std::string& object,
                          const std::string& name, std::uint64_t value) {
  const damage_detail::OpenFile open(file);
  const hid_t holder = H5Oopen(open.get(), object.c_str(), H5P_DEFAULT);
  damage_detail::check(holder < 0 ? -1 : 0, "opening " + object);
  const hid_t attribute = H5Aopen(holder, name.c_str(), H5P_DEFAULT);
  damage_detail::check(attribute < 0 ? -1 : 0, "opening attribute " + name + " of " + object);
  damage_detail::check(H5Awrite(attribute, H5T_NATIVE_UINT64, &value), "writing " + name);
  H5Aclose(attribute);
  H5Oclose(holder);
}

// Replaces the dataset at `path` with a float64 one of `rows` rows.
inline void replace_with_rows(const std::filesystem::path& file, const std::string& path,
                              hsize_t rows) {
  const damage_detail::OpenFile open(file);
  damage_detail::check(H5Ldelete(open.get(), path.c_str(), H5P_DEFAULT), "removing " + path);
  const hid_t space = H5Screate_simple(1, &rows, nullptr);
  const hid_t dataset = H5Dcreate2(open.get(), path.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT,
                                   H5P_DEFAULT, H5P_DEFAULT);
  damage_detail::check(dataset < 0 ? -1 : 0, "creating " + path);
  H5Dclose(dataset);
  H5Sclose(space);
}

}  // namespace grip::io::testing
