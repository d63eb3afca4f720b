// Fuzz target: dataset files, opened with DatasetReader and read the way `grip inspect` reads
// them. Anything but a DatasetError is a finding. HDF5 itself parses the file's structure, so
// this mostly exercises the layout checks and the reads behind them.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz/fuzz_input.hpp"
#include "io/dataset_error.hpp"
#include "io/dataset_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    grip::io::DatasetReader reader(grip::fuzz::write_input(data, size, "data.h5"));
    reader.job_id();
    reader.provenance();
    const grip::io::DatasetLayout& layout = reader.layout();
    for (std::uint32_t o = 0; o < layout.objects.size(); ++o) reader.object(o);
    for (std::uint32_t g = 0; g < layout.grippers.size(); ++g) reader.gripper(g);
    reader.done();
    reader.damage();
    reader.candidates();
    for (std::uint64_t id = 0; id < layout.candidate_count && id < 4; ++id) {
      reader.trajectory(id);
      reader.stress(id);
    }
  } catch (const grip::io::DatasetError&) {
  }
  return 0;
}
