// Fuzz target: gripper description files (grip synth --gripper FILE.toml, a job's [[grippers]]
// description). The input is the description; it may name the small valid finger written
// beside it (finger.vtk: a 12 x 6 x 30 mm prism of three tets, in millimetres), or anything
// else. Anything but the config::ConfigError the reader documents is a finding.
#include <cstddef>
#include <cstdint>
#include <fstream>

#include "fuzz/fuzz_input.hpp"
#include "src/config/config.hpp"
#include "src/grippers/gripper_description.hpp"

namespace {

void write_finger() {
  std::ofstream(grip::fuzz::input_folder() / "finger.vtk")
      << "# vtk DataFile Version 4.2\nfinger\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 6 double\n"
         "0 0 0\n12 0 0\n0 6 0\n0 0 30\n12 0 30\n0 6 30\n"
         "CELLS 3 15\n4 0 1 2 3\n4 1 2 3 4\n4 2 3 4 5\nCELL_TYPES 3\n10\n10\n10\n";
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool written = (write_finger(), true);
  (void)written;
  try {
    grip::grippers::load_gripper_description(grip::fuzz::write_input(data, size, "gripper.toml"));
  } catch (const grip::config::ConfigError&) {
  }
  return 0;
}
