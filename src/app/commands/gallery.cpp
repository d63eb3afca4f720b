// grip asset gallery --out DIR: every object category and every gripper as meshes, for a look.
#include <spdlog/spdlog.h>

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <system_error>
#include <string>

#include <Eigen/Core>

#include "src/app/commands.hpp"
#include "src/geometry/mesh_io.hpp"
#include "src/geometry/tet_quality.hpp"
#include "src/grippers/kinematic_tree.hpp"
#include "src/grippers/leap_hand.hpp"
#include "src/grippers/parallel_gripper.hpp"
#include "src/objects/object_library.hpp"

namespace grip::commands {
namespace {

void write_parallel_gripper(const std::filesystem::path& folder,
                            const grippers::ParallelGripper& gripper) {
  geometry::write_obj(folder / (gripper.name + "_open.obj"), gripper.surface(gripper.max_opening));
  geometry::write_obj(folder / (gripper.name + "_closed.obj"),
                      gripper.surface(gripper.min_opening));
}

// Open: every joint at 0 (clamped into its limits); closed: every joint at the middle of its
// range, which curls the fingers halfway and leaves abduction centred.
void write_hand(const std::filesystem::path& folder, const std::string& name,
                const grippers::KinematicTree& hand) {
  const Eigen::VectorXd open = hand.clamp_to_limits(Eigen::VectorXd::Zero(hand.dof_count()));
  const Eigen::VectorXd closed = 0.5 * (hand.lower_limits() + hand.upper_limits());
  const Eigen::Isometry3d base = Eigen::Isometry3d::Identity();
  geometry::write_obj(folder / (name + "_open.obj"), hand.posed_surface(hand.link_poses(base, open)));
  geometry::write_obj(folder / (name + "_closed.obj"),
                      hand.posed_surface(hand.link_poses(base, closed)));
}

}  // namespace

int asset_gallery(const AssetGalleryArgs& args) {
  const std::filesystem::path out = args.out_dir;
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

  const grippers::ParallelGripper umi = grippers::make_umi_soft_gripper();
  const geometry::TetQuality quality = geometry::tet_quality(umi.soft_finger->mesh);
  spdlog::info("fin-ray finger: {} vertices, {} tets, dihedral angles {:.1f} to {:.1f} deg, {} "
               "inverted, {} mount vertices",
               umi.soft_finger->mesh.vertices.rows(), umi.soft_finger->mesh.tets.rows(),
               quality.min_dihedral_deg, quality.max_dihedral_deg, quality.inverted_count,
               umi.soft_finger->mount_vertices.size());
  write_parallel_gripper(grippers_dir, umi);
  geometry::write_msh(grippers_dir / "fin_ray_finger.msh", umi.soft_finger->mesh);
  geometry::write_vtu(grippers_dir / "fin_ray_finger.vtu", umi.soft_finger->mesh);
  write_parallel_gripper(grippers_dir, grippers::make_rigid_jaw_gripper());

  // The hand packages are regenerated here (identical to assets/grippers/leap_*), then loaded
  // back through the URDF path a user's own hand takes.
  for (const auto& [side, name] : {std::pair{grippers::HandSide::kRight, "leap_right"},
                                   std::pair{grippers::HandSide::kLeft, "leap_left"}}) {
    const grippers::LeapHandFiles files = grippers::write_leap_hand(hands_dir / name, side);
    write_hand(grippers_dir, name, grippers::KinematicTree::from_urdf(files.urdf));
  }
  spdlog::info("wrote {} object meshes to {}, gripper meshes (open and closed) to {}, and the "
               "LEAP-style hand packages to {}",
               object_count, objects_dir.string(), grippers_dir.string(), hands_dir.string());
  return 0;
}

}  // namespace grip::commands
