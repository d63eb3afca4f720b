#pragma once
// HDF5 enumeration types for the Status and FailureKind columns, so that a reader (h5py,
// h5dump) sees their names, not bare numbers. File types are little-endian bytes; memory
// types native bytes; HDF5 converts between them by name.
#include "io/hdf5.hpp"

namespace grip::io {

h5::Handle status_type(bool file);
h5::Handle failure_kind_type(bool file);

}  // namespace grip::io
