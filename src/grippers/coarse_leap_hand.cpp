#include "src/grippers/coarse_leap_hand.hpp"

#include <unistd.h>

#include <filesystem>
#include <string>

#include "src/geometry/mesh_io.hpp"
#include "src/geometry/primitives.hpp"

namespace grip::grippers {

HandModel coarse_leap_hand(HandSide side) {
  // One folder per process: tests may build the hand side by side.
  const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / ("grip_coarse_leap_" + std::to_string(::getpid()));
  const LeapHandFiles files = write_leap_hand(folder, side);
  for (const char* stem : {"proximal", "thumb_proximal", "intermediate", "distal"}) {
    const std::filesystem::path file = folder / "meshes" / (std::string(stem) + ".obj");
    const geometry::SurfaceMesh full = geometry::read_surface_mesh(file);
    const Eigen::Vector3d lower = full.vertices.colwise().minCoeff();
    const Eigen::Vector3d upper = full.vertices.colwise().maxCoeff();
    geometry::SurfaceMesh coarse = geometry::make_capsule(upper.y(), upper.x() - lower.x(), 8, 2);
    coarse.vertices.col(0).array() += lower.x();
    geometry::write_obj(file, coarse);
  }
  HandModel hand = load_hand_model(files.urdf, files.points);
  std::filesystem::remove_all(folder);  // the model holds the meshes
  return hand;
}

}  // namespace grip::grippers
