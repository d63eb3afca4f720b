// Fuzz target: the values stored in a grip dataset, with HDF5's own structure intact. Whole-file
// mutation (fuzz_dataset) mostly damages HDF5's metadata, where HDF5 1.10 itself crashes within
// seconds; this target keeps every metadata byte of a valid dataset (the template, a current
// format dataset of the seed corpus) and lets the input replace only the stored values, in file
// order: indices, sizes, flags, checksums, poses and forces, the things grip itself checks.
// The input is those values; a shorter one leaves the template's values after it. Anything but
// a DatasetError is a finding.
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <vector>

#include "fuzz/dataset_reads.hpp"
#include "fuzz/dataset_storage.hpp"
#include "fuzz/fuzz_input.hpp"
#include "io/dataset_error.hpp"

namespace {

struct Template {
  std::vector<std::uint8_t> bytes;
  std::vector<grip::fuzz::StorageRange> ranges;
};

const Template& dataset_template() {
  static const Template loaded = [] {
    Template t;
    std::ifstream in(GRIP_FUZZ_DATASET_TEMPLATE, std::ios::binary);
    t.bytes.assign(std::istreambuf_iterator<char>(in), {});
    t.ranges = grip::fuzz::storage_ranges(GRIP_FUZZ_DATASET_TEMPLATE);
    return t;
  }();
  return loaded;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const Template& base = dataset_template();
  std::vector<std::uint8_t> file = base.bytes;
  grip::fuzz::overwrite_values(file, base.ranges, data, size);
  try {
    grip::fuzz::read_like_inspect(grip::fuzz::write_input(file.data(), file.size(), "data.h5"));
  } catch (const grip::io::DatasetError&) {
  }
  return 0;
}
