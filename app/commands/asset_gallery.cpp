// grip asset gallery --out DIR: every object category and every gripper as meshes, for a look.
#include <spdlog/spdlog.h>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <system_error>

#include <Eigen/Core>

#include "app/cli/command_line.hpp"
#include "app/commands/commands.hpp"
#include "src/geometry/mesh_io.hpp"
#include "src/geometry/tet_quality.hpp"
#include "src/grippers/gripper_registry.hpp"
#include "src/grippers/kinematic_tree.hpp"
#include "src/grippers/leap_hand.hpp"
#include "src/objects/object_library.hpp"

namespace grip::commands {
namespace {

void write_parallel_gripper(const std::filesystem::path& folder,
                            const grippers::ParallelGripper& gripper) {
  geometry::write_obj(folder / (gripper.name + "_open.obj"), gripper.surface(gripper.max_opening));
  geometry::write_obj(folder / (gripper.name + "_closed.obj"),
                      gripper.surface(gripper.min_opening));
}

// The finger's tet mesh as Gmsh 2.2 and VTU, `stem` + extension, and its figures in the log.
void write_fin_ray_finger(const std::filesystem::path& stem, const std::string& title,
                          const grippers::FinRayFinger& finger) {
  const geometry::TetQuality quality = geometry::tet_quality(finger.mesh);
  spdlog::info(
      "{}: {} vertices, {} tets, dihedral angles {:.1f} to {:.1f} deg, {} inverted, {} mount "
      "vertices",
      title, finger.mesh.vertices.rows(), finger.mesh.tets.rows(), quality.min_dihedral_deg,
      quality.max_dihedral_deg, quality.inverted_count, finger.mount_vertices.size());
  geometry::write_msh(std::filesystem::path(stem).concat(".msh"), finger.mesh);
  geometry::write_vtu(std::filesystem::path(stem).concat(".vtu"), finger.mesh);
}

// Open: every joint at 0 (clamped into its limits); closed: every joint at the middle of its
// range, which curls the fingers halfway and leaves abduction centred.
void write_hand(const std::filesystem::path& folder, const std::string& name,
                const grippers::KinematicTree& hand) {
  const Eigen::VectorXd open = hand.clamp_to_limits(Eigen::VectorXd::Zero(hand.dof_count()));
  const Eigen::VectorXd closed = 0.5 * (hand.lower_limits() + hand.upper_limits());
  const Eigen::Isometry3d base = Eigen::Isometry3d::Identity();
  geometry::write_obj(folder / (name + "_open.obj"),
                      hand.posed_surface(hand.link_poses(base, open)));
  geometry::write_obj(folder / (name + "_closed.obj"),
                      hand.posed_surface(hand.link_poses(base, closed)));
}

int asset_gallery(const std::string& out_dir) {
  const std::filesystem::path out = out_dir;
  const std::filesystem::path objects_dir = out / "objects";
  const std::filesystem::path grippers_dir = out / "grippers";
  const std::filesystem::path hands_dir = out / "hands";
  for (const std::filesystem::path& dir : {objects_dir, grippers_dir, hands_dir}) {
    std::error_code error;
    std::filesystem::create_directories(dir, error);
    if (error) {
      throw std::runtime_error("grip asset gallery: cannot create '" + dir.string() +
                               "': " + error.message() + "; choose another --out folder");
    }
  }

  // One default instance per category: the shape drawn with seed 0.
  int object_count = 0;
  for (const objects::ObjectCategory category : objects::all_object_categories()) {
    const objects::ObjectShape shape = objects::sample_shape(category, std::uint64_t{0});
    geometry::write_obj(objects_dir / (std::string(objects::category_name(category)) + ".obj"),
                        objects::generate_surface(shape));
    ++object_count;
  }

  for (const grippers::GripperType& type : grippers::gripper_types()) {
    if (type.is_hand()) continue;
    const grippers::ParallelGripper gripper = grippers::make_parallel_gripper(type.kind);
    if (gripper.soft_finger) {
      write_fin_ray_finger(grippers_dir / "fin_ray_finger", "fin-ray finger", *gripper.soft_finger);
      // grip's first finger, described from this file by jobs/grippers/fin-ray-80mm.toml.
      write_fin_ray_finger(grippers_dir / "fin_ray_finger_80mm", "80 mm fin-ray finger",
                           grippers::make_fin_ray_finger(grippers::fin_ray_80mm_options()));
    }
    write_parallel_gripper(grippers_dir, gripper);
  }

  // The hand packages are regenerated here (identical to assets/grippers/leap_*), then loaded
  // back through the URDF path a user's own hand takes.
  for (const auto& [side, name] : {std::pair{grippers::HandSide::kRight, "leap_right"},
                                   std::pair{grippers::HandSide::kLeft, "leap_left"}}) {
    const grippers::LeapHandFiles files = grippers::write_leap_hand(hands_dir / name, side);
    write_hand(grippers_dir, name, grippers::KinematicTree::from_urdf(files.urdf));
  }
  spdlog::info(
      "wrote {} object meshes to {}, gripper meshes (open and closed) to {}, and the "
      "LEAP-style hand packages to {}",
      object_count, objects_dir.string(), grippers_dir.string(), hands_dir.string());
  return 0;
}

}  // namespace

void declare_asset_gallery(cli::Command& asset) {
  auto out_dir = std::make_shared<std::string>();
  cli::Command gallery = asset.subcommand(
      "gallery", "Write every object category and gripper (open and closed) as .obj meshes");
  gallery.option("--out", *out_dir, "Output folder").required().check(cli::Check::output_folder());
  gallery.on_run([out_dir] { return asset_gallery(*out_dir); });
}

}  // namespace grip::commands
