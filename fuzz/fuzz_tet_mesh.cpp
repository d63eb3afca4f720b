// Fuzz target: tet mesh files of a soft body the user brings. The first byte picks the format
// ('0' legacy VTK, '1' Gmsh, '2' MEDIT, by its value modulo 3), the rest is the file; a mesh
// that reads is then checked as a soft body. Anything but the std::runtime_error both
// document is a finding.
#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "fuzz/fuzz_input.hpp"
#include "src/geometry/tet_mesh_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const char* const kNames[] = {"finger.vtk", "finger.msh", "finger.mesh"};
  try {
    grip::geometry::TetMesh mesh = grip::geometry::read_tet_mesh(
        grip::fuzz::write_input(data + 1, size - 1, kNames[data[0] % 3]));
    grip::geometry::check_soft_body_mesh(mesh, "finger");
  } catch (const std::runtime_error&) {
  }
  return 0;
}
