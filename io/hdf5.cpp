#include "io/hdf5.hpp"

#include <algorithm>
#include <numeric>

#include "io/dataset_error.hpp"

namespace grip::io::h5 {

void Handle::reset() {
  if (id_ >= 0 && closer_ != nullptr) closer_(id_);
  id_ = -1;
}

void silence_errors() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

namespace {

// Collects the stack's messages, outermost call first.
herr_t collect_message(unsigned index, const H5E_error2_t* error, void* data) {
  auto* messages = static_cast<std::vector<std::string>*>(data);
  (void)index;
  if (error->desc != nullptr && error->desc[0] != '\0') messages->emplace_back(error->desc);
  return 0;
}

}  // namespace

std::string last_error() {
  std::vector<std::string> messages;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, collect_message, &messages);
  H5Eclear2(H5E_DEFAULT);
  if (messages.empty()) return "";
  // The deepest message names the cause ("truncated file: eof = ..."), the outermost the call.
  const std::string& deepest = messages.back();
  return messages.size() > 1 && deepest != messages.front() ? messages.front() + ": " + deepest
                                                            : deepest;
}

void check(herr_t status, const std::string& what) {
  if (status < 0) {
    const std::string reason = last_error();
    throw DatasetError(reason.empty() ? what : what + ": " + reason);
  }
}

hid_t checked(hid_t id, const std::string& what) {
  check(id < 0 ? -1 : 0, what);
  return id;
}

Handle file_handle(hid_t id, const std::string& what) { return {checked(id, what), H5Fclose}; }
Handle group_handle(hid_t id, const std::string& what) { return {checked(id, what), H5Gclose}; }
Handle dataset_handle(hid_t id, const std::string& what) { return {checked(id, what), H5Dclose}; }

Handle open_dataset(hid_t file, const std::string& path) {
  return dataset_handle(H5Dopen2(file, path.c_str(), H5P_DEFAULT), "opening " + path);
}
Handle space_handle(hid_t id, const std::string& what) { return {checked(id, what), H5Sclose}; }
Handle type_handle(hid_t id, const std::string& what) { return {checked(id, what), H5Tclose}; }
Handle plist_handle(hid_t id, const std::string& what) { return {checked(id, what), H5Pclose}; }
Handle attribute_handle(hid_t id, const std::string& what) { return {checked(id, what), H5Aclose}; }

Handle string_type(std::size_t size) {
  Handle type = type_handle(H5Tcopy(H5T_C_S1), "copying the string type");
  check(H5Tset_size(type, std::max<std::size_t>(size, 1)), "sizing a string type");
  check(H5Tset_strpad(type, H5T_STR_NULLPAD), "padding a string type");
  return type;
}

bool exists(hid_t location, const std::string& path) {
  return H5Lexists(location, path.c_str(), H5P_DEFAULT) > 0;
}

namespace {

void write_scalar_attribute(hid_t object, const std::string& name, hid_t file_type,
                            hid_t memory_type, const void* value) {
  const Handle space = space_handle(H5Screate(H5S_SCALAR), "creating a scalar space");
  const Handle attribute =
      attribute_handle(H5Acreate2(object, name.c_str(), file_type, space, H5P_DEFAULT, H5P_DEFAULT),
                       "creating attribute '" + name + "'");
  check(H5Awrite(attribute, memory_type, value), "writing attribute '" + name + "'");
}

Handle open_attribute(hid_t object, const std::string& name) {
  if (H5Aexists(object, name.c_str()) <= 0) {
    throw DatasetError("attribute '" + name + "' is missing");
  }
  return attribute_handle(H5Aopen(object, name.c_str(), H5P_DEFAULT),
                          "opening attribute '" + name + "'");
}

}  // namespace

void write_attribute(hid_t object, const std::string& name, const std::string& value) {
  const Handle type = string_type(value.size());
  std::string padded = value;
  padded.resize(std::max<std::size_t>(value.size(), 1), '\0');
  write_scalar_attribute(object, name, type, type, padded.data());
}

void write_attribute(hid_t object, const std::string& name, double value) {
  write_scalar_attribute(object, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value);
}

void write_attribute(hid_t object, const std::string& name, std::uint64_t value) {
  write_scalar_attribute(object, name, H5T_STD_U64LE, H5T_NATIVE_UINT64, &value);
}

std::string read_string_attribute(hid_t object, const std::string& name) {
  const Handle attribute = open_attribute(object, name);
  const Handle type = type_handle(H5Aget_type(attribute), "reading the type of '" + name + "'");
  if (H5Tget_class(type) != H5T_STRING || H5Tis_variable_str(type) > 0) {
    throw DatasetError("attribute '" + name + "' is not a fixed-length string");
  }
  const std::size_t size = H5Tget_size(type);
  std::string value(size, '\0');
  const Handle memory = string_type(size);
  check(H5Aread(attribute, memory, value.data()), "reading attribute '" + name + "'");
  value.resize(value.find('\0') == std::string::npos ? size : value.find('\0'));
  return value;
}

double read_double_attribute(hid_t object, const std::string& name) {
  const Handle attribute = open_attribute(object, name);
  double value = 0;
  check(H5Aread(attribute, H5T_NATIVE_DOUBLE, &value), "reading attribute '" + name + "'");
  return value;
}

std::uint64_t read_uint_attribute(hid_t object, const std::string& name) {
  const Handle attribute = open_attribute(object, name);
  std::uint64_t value = 0;
  check(H5Aread(attribute, H5T_NATIVE_UINT64, &value), "reading attribute '" + name + "'");
  return value;
}

std::vector<hsize_t> dims(hid_t dataset) {
  const Handle space = space_handle(H5Dget_space(dataset), "reading a dataset's shape");
  const int rank = H5Sget_simple_extent_ndims(space);
  std::vector<hsize_t> result(static_cast<std::size_t>(std::max(rank, 0)));
  if (rank > 0) H5Sget_simple_extent_dims(space, result.data(), nullptr);
  return result;
}

std::size_t element_count(const std::vector<hsize_t>& dims) {
  return std::accumulate(dims.begin(), dims.end(), std::size_t{1},
                         [](std::size_t a, hsize_t b) { return a * b; });
}

Handle transfer_properties(bool collective) {
  Handle transfer = plist_handle(H5Pcreate(H5P_DATASET_XFER), "creating transfer properties");
  if (collective) {
    check(H5Pset_dxpl_mpio(transfer, H5FD_MPIO_COLLECTIVE), "choosing collective transfers");
  } else {
    check(H5Pset_dxpl_mpio(transfer, H5FD_MPIO_INDEPENDENT), "choosing independent transfers");
  }
  return transfer;
}

std::vector<std::string> read_strings(hid_t dataset) {
  const Handle type = type_handle(H5Dget_type(dataset), "reading a string dataset's type");
  if (H5Tget_class(type) != H5T_STRING || H5Tis_variable_str(type) > 0) {
    throw DatasetError("a dataset expected to hold fixed-length strings holds something else");
  }
  const std::size_t size = H5Tget_size(type);
  std::size_t count = 1;
  for (const hsize_t d : dims(dataset)) count *= d;
  std::vector<char> buffer(count * size);
  if (count > 0) {
    const Handle memory = string_type(size);
    check(H5Dread(dataset, memory, H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()),
          "reading strings");
  }
  std::vector<std::string> result(count);
  for (std::size_t i = 0; i < count; ++i) {
    const char* begin = buffer.data() + i * size;
    result[i].assign(begin, std::find(begin, begin + size, '\0'));
  }
  return result;
}

}  // namespace grip::io::h5
