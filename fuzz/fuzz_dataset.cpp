// Fuzz target: dataset files, opened with DatasetReader and read the way `grip inspect` reads
// them. Anything but a DatasetError is a finding. HDF5 itself parses the file's structure, so
// most inputs stop (or crash) in HDF5; fuzz_dataset_values fuzzes the stored values alone.
#include <cstddef>
#include <cstdint>

#include "fuzz/dataset_reads.hpp"
#include "fuzz/fuzz_input.hpp"
#include "io/dataset_error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    grip::fuzz::read_like_inspect(grip::fuzz::write_input(data, size, "data.h5"));
  } catch (const grip::io::DatasetError&) {
  }
  return 0;
}
