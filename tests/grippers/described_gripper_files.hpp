#pragma once
// A soft gripper description for the tests, as a user would bring one: a box finger 20 mm wide,
// 10 mm thick and 50 mm long (5 mm cells, 480 tets), meshed in millimetres along other axes than
// grip's (the tip along the file's +y, closing along +x), written as a legacy VTK file beside
// its description.
#include <filesystem>
#include <fstream>
#include <string>

#include <Eigen/Core>

#include "src/geometry/mesh.hpp"
#include "src/scene/primitives.hpp"

namespace grip::testing {

// The finger in the file's frame and units: x from -5 to 5 (closing along +x), y from -25 to 25
// (mount at y = -25, tip at 25), z from -10 to 10.
inline geometry::TetMesh box_finger_mm() {
  return scene::box_tets(Eigen::Vector3d(10.0, 50.0, 20.0), 5.0);
}

inline void write_vtk_tets(const std::filesystem::path& file, const geometry::TetMesh& mesh) {
  std::ofstream out(file);
  out << "# vtk DataFile Version 4.2\ntest finger\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS "
      << mesh.vertices.rows() << " double\n";
  out.precision(17);
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
    out << mesh.vertices(v, 0) << ' ' << mesh.vertices(v, 1) << ' ' << mesh.vertices(v, 2) << '\n';
  }
  out << "CELLS " << mesh.tets.rows() << ' ' << 5 * mesh.tets.rows() << '\n';
  for (Eigen::Index t = 0; t < mesh.tets.rows(); ++t) {
    out << "4 " << mesh.tets(t, 0) << ' ' << mesh.tets(t, 1) << ' ' << mesh.tets(t, 2) << ' '
        << mesh.tets(t, 3) << '\n';
  }
  out << "CELL_TYPES " << mesh.tets.rows() << '\n';
  for (Eigen::Index t = 0; t < mesh.tets.rows(); ++t) out << "10\n";
}

// The description of the box finger in `mesh_file` (a name beside the description), with
// `mount` as the [finger.mount] table's body and `scale` as the finger's scale.
inline std::string described_gripper_text(const std::string& mesh_file = "finger.vtk",
                                          const std::string& mount = "depth = 0.001",
                                          const std::string& scale = "0.001") {
  return "[gripper]\nname = \"test-soft-jaws\"\nopening = [0.0, 0.08]\ngrasp_depth = 0.02\n\n"
         "[finger]\nmesh = \"" +
         mesh_file + "\"\nscale = " + scale +
         "\nclosing_axis = [1, 0, 0]\ntip_axis = [0, 1, 0]\n\n[finger.mount]\n" + mount +
         "\n\n[finger.material]\nyoungs_modulus = 2e6\npoisson_ratio = 0.4\ndensity = 1100\n"
         "friction = 1.0\n";
}

// Writes the box finger and its description into `folder`; returns the description's path.
inline std::filesystem::path write_described_gripper(const std::filesystem::path& folder) {
  write_vtk_tets(folder / "finger.vtk", box_finger_mm());
  const std::filesystem::path description = folder / "gripper.toml";
  std::ofstream(description) << described_gripper_text();
  return description;
}

}  // namespace grip::testing
