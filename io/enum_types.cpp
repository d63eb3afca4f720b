#include "io/enum_types.hpp"

#include <string>

#include "io/candidate_record.hpp"

namespace grip::io {

namespace {

template <typename Enum>
h5::Handle enum_type(bool file, std::uint8_t count) {
  h5::Handle type = h5::type_handle(H5Tenum_create(file ? H5T_STD_U8LE : H5T_NATIVE_UINT8),
                                    "creating an enumeration type");
  for (std::uint8_t value = 0; value < count; ++value) {
    const std::string name(to_string(static_cast<Enum>(value)));
    h5::check(H5Tenum_insert(type, name.c_str(), &value), "naming enumeration value " + name);
  }
  return type;
}

}  // namespace

h5::Handle status_type(bool file) { return enum_type<Status>(file, 3); }

h5::Handle failure_kind_type(bool file) { return enum_type<FailureKind>(file, kFailureKindCount); }

}  // namespace grip::io
