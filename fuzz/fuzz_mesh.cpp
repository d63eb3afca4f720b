// Fuzz target: surface mesh files. The first byte picks the format ('0' OBJ, '1' STL, '2' PLY,
// '3' OFF, by its value modulo 4), the rest is the file. Anything but the std::runtime_error
// read_surface_mesh documents is a finding.
#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "fuzz/fuzz_input.hpp"
#include "src/geometry/mesh_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const char* const kNames[] = {"mesh.obj", "mesh.stl", "mesh.ply", "mesh.off"};
  try {
    grip::geometry::read_surface_mesh(
        grip::fuzz::write_input(data + 1, size - 1, kNames[data[0] % 4]));
  } catch (const std::runtime_error&) {
  }
  return 0;
}
