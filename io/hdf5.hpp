#pragma once
// Thin RAII and error helpers over the HDF5 C API, shared by the dataset writer and reader:
// owned identifiers, checked calls that throw DatasetError with HDF5's own reason, and typed
// attribute and string helpers.
#include <hdf5.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace grip::io::h5 {

// Owns one HDF5 identifier and closes it with the matching H5*close function.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, -1)), closer_(other.closer_) {}
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, -1);
      closer_ = other.closer_;
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { reset(); }

  hid_t get() const { return id_; }
  operator hid_t() const { return id_; }  // NOLINT: handles pass straight into the C API
  void reset();

 private:
  hid_t id_ = -1;
  Closer closer_ = nullptr;
};

// Turns HDF5's automatic error printing off for this process; errors become exceptions.
void silence_errors();

// The innermost message on HDF5's error stack (e.g. "truncated file: eof = ..."), or "".
std::string last_error();

// Throws DatasetError("<what>: <HDF5's reason>") when status or id is negative.
void check(herr_t status, const std::string& what);
hid_t checked(hid_t id, const std::string& what);

Handle file_handle(hid_t id, const std::string& what);
Handle group_handle(hid_t id, const std::string& what);
Handle dataset_handle(hid_t id, const std::string& what);
// Opens the dataset at `path` in `file` (DatasetError "opening <path>" if it cannot).
Handle open_dataset(hid_t file, const std::string& path);
Handle space_handle(hid_t id, const std::string& what);
Handle type_handle(hid_t id, const std::string& what);
Handle plist_handle(hid_t id, const std::string& what);
Handle attribute_handle(hid_t id, const std::string& what);

// Fixed-length, NUL-padded string type of `size` bytes (at least 1).
Handle string_type(std::size_t size);

bool exists(hid_t location, const std::string& path);

// Attributes. The writers are collective in parallel HDF5: every rank passes the same value.
void write_attribute(hid_t object, const std::string& name, const std::string& value);
void write_attribute(hid_t object, const std::string& name, double value);
void write_attribute(hid_t object, const std::string& name, std::uint64_t value);
std::string read_string_attribute(hid_t object, const std::string& name);
double read_double_attribute(hid_t object, const std::string& name);
std::uint64_t read_uint_attribute(hid_t object, const std::string& name);

// The dimensions of a dataset, and the number of elements such dimensions hold.
std::vector<hsize_t> dims(hid_t dataset);
std::size_t element_count(const std::vector<hsize_t>& dims);

// MPI-IO data transfer properties: collective (every rank joins each write) or independent.
Handle transfer_properties(bool collective);

// Reads a whole numeric dataset, converted to the memory type of T.
template <typename T>
std::vector<T> read_all(hid_t dataset, hid_t memory_type) {
  std::size_t count = 1;
  for (const hsize_t d : dims(dataset)) count *= d;
  std::vector<T> values(count);
  if (count > 0) {
    check(H5Dread(dataset, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
          "reading a dataset");
  }
  return values;
}

// Reads a whole fixed-length string dataset (scalar or 1-D, or 2-D for string tables).
std::vector<std::string> read_strings(hid_t dataset);

}  // namespace grip::io::h5
