#include "io/column.hpp"

#include <cstring>
#include <limits>
#include <numeric>
#include <string>
#include <type_traits>

#include "io/dataset_error.hpp"
#include "io/enum_types.hpp"

namespace grip::io {

h5::Handle element_type(Element element, bool file, std::size_t width) {
  // Predefined types are not closed: a handle without a closer.
  const auto predefined = [](hid_t type) { return h5::Handle(type, nullptr); };
  switch (element) {
    case Element::kFloat64:
      return predefined(file ? H5T_IEEE_F64LE : H5T_NATIVE_DOUBLE);
    case Element::kFloat32:
      return predefined(file ? H5T_IEEE_F32LE : H5T_NATIVE_FLOAT);
    case Element::kInt32:
      return predefined(file ? H5T_STD_I32LE : H5T_NATIVE_INT32);
    case Element::kInt64:
      return predefined(file ? H5T_STD_I64LE : H5T_NATIVE_INT64);
    case Element::kUint32:
      return predefined(file ? H5T_STD_U32LE : H5T_NATIVE_UINT32);
    case Element::kUint8:
      return predefined(file ? H5T_STD_U8LE : H5T_NATIVE_UINT8);
    case Element::kStatus:
      return status_type(file);
    case Element::kFailureKind:
      return failure_kind_type(file);
    case Element::kString:
      return h5::string_type(width);
  }
  return {};
}

std::array<std::byte, 8> fill_bytes(Element element, Fill fill) {
  std::array<std::byte, 8> bytes{};
  if (fill != Fill::kNaN) return bytes;
  if (element == Element::kFloat32) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::memcpy(bytes.data(), &nan, sizeof nan);
  } else {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    std::memcpy(bytes.data(), &nan, sizeof nan);
  }
  return bytes;
}

Values read_values(hid_t dataset, Element element) {
  Values values = empty_values(value_index(element));
  const h5::Handle memory_type = element_type(element, false);
  std::visit(
      [&](auto& v) {
        using T = typename std::remove_cvref_t<decltype(v)>::value_type;
        if constexpr (std::is_same_v<T, std::string>) {
          v = h5::read_strings(dataset);
        } else {
          v = h5::read_all<T>(dataset, memory_type);
        }
      },
      values);
  return values;
}

Values read_row_values(hid_t dataset, const std::string& path, std::uint64_t row, Element element) {
  return read_rows_values(dataset, path, row, 1, element);
}

Values read_rows_values(hid_t dataset, const std::string& path, std::uint64_t first,
                        std::uint64_t rows, Element element) {
  std::vector<hsize_t> count = h5::dims(dataset);
  if (count.empty() || first > count[0] || rows > count[0] - first) {
    throw DatasetError(path + " has no rows " + std::to_string(first) + " to " +
                       std::to_string(first + rows - 1));
  }
  std::vector<hsize_t> start(count.size(), 0);
  start[0] = first;
  count[0] = rows;
  hsize_t size = 1;
  for (const hsize_t d : count) size *= d;
  Values values = empty_values(value_index(element));
  std::visit([&](auto& v) { v.resize(size); }, values);
  if (size == 0) return values;
  const std::string which =
      rows == 1 ? "row " + std::to_string(first)
                : "rows " + std::to_string(first) + " to " + std::to_string(first + rows - 1);
  const h5::Handle file_space = h5::space_handle(H5Dget_space(dataset), "selecting a row");
  h5::check(
      H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr),
      "selecting " + which + " of " + path);
  const h5::Handle memory_space =
      h5::space_handle(H5Screate_simple(1, &size, nullptr), "shaping a row");
  const h5::Handle memory_type = element_type(element, false);
  h5::check(
      H5Dread(dataset, memory_type, memory_space, file_space, H5P_DEFAULT, number_data(values)),
      "reading " + which + " of " + path);
  return values;
}

std::size_t element_bytes(Element element) {
  return std::visit(
      [](const auto& v) -> std::size_t {
        using T = typename std::remove_cvref_t<decltype(v)>::value_type;
        return std::is_arithmetic_v<T> ? sizeof(T) : 0;
      },
      empty_values(value_index(element)));
}

Sizes Sizes::of(const DatasetLayout& layout) {
  Sizes sizes;
  sizes.frames = layout.frames();
  sizes.max_hands = layout.max_hands;
  sizes.max_joints = layout.max_joints;
  sizes.max_fingers = layout.max_fingers;
  return sizes;
}

Sizes Sizes::of(const DatasetLayout& layout, std::uint32_t object, std::uint32_t gripper) {
  Sizes sizes = of(layout);
  sizes.object = layout.objects[object];
  sizes.gripper = layout.grippers[gripper];
  return sizes;
}

Sizes Sizes::of_candidate(const DatasetLayout& layout, std::uint64_t id) {
  return of(layout, layout.object[id], layout.gripper[id]);
}

std::size_t row_size(const Column& column, const Sizes& sizes) {
  const Dims extents = column.extents(sizes);
  return std::accumulate(extents.begin(), extents.end(), std::size_t{1},
                         [](std::size_t a, hsize_t b) { return a * b; });
}

std::size_t record_size(const Column& column, const Sizes& sizes) {
  if (column.per_hand == nullptr) return row_size(column, sizes);
  return std::size_t{sizes.gripper.hands} * column.per_hand(sizes.gripper);
}

}  // namespace grip::io
