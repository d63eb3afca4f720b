#include "src/grippers/parallel_gripper.hpp"

#include <numbers>
#include <stdexcept>
#include <string>

#include "src/geometry/boundary_surface.hpp"
#include "src/geometry/primitives.hpp"
#include "src/grippers/surface_merge.hpp"

namespace grip::grippers {

Eigen::Isometry3d ParallelGripper::finger_pose(Jaw jaw, double opening) const {
  if (!(opening >= min_opening && opening <= max_opening)) {
    throw std::out_of_range(name + ": jaw opening " + std::to_string(opening) + " m is outside [" +
                            std::to_string(min_opening) + ", " + std::to_string(max_opening) +
                            "] m");
  }
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  if (jaw == Jaw::kPositive) {
    pose.translation() = Eigen::Vector3d(0.0, 0.5 * opening, 0.0);
  } else {
    pose.linear() =
        Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    pose.translation() = Eigen::Vector3d(0.0, -0.5 * opening, 0.0);
  }
  return pose;
}

geometry::SurfaceMesh ParallelGripper::surface(double opening) const {
  geometry::SurfaceMesh mesh;
  append_transformed(mesh, finger_surface, finger_pose(Jaw::kPositive, opening));
  append_transformed(mesh, finger_surface_of(Jaw::kNegative), finger_pose(Jaw::kNegative, opening));
  return mesh;
}

geometry::TetMesh ParallelGripper::finger_tets(double opening) const {
  geometry::TetMesh both;
  if (!soft_finger) return both;
  for (const Jaw jaw : {Jaw::kPositive, Jaw::kNegative}) {
    const geometry::TetMesh finger = soft_finger_of(jaw)->mesh;
    const Eigen::Isometry3d pose = finger_pose(jaw, opening);
    const Eigen::Index v0 = both.vertices.rows();
    const Eigen::Index t0 = both.tets.rows();
    both.vertices.conservativeResize(v0 + finger.vertices.rows(), 3);
    both.tets.conservativeResize(t0 + finger.tets.rows(), 4);
    for (Eigen::Index i = 0; i < finger.vertices.rows(); ++i) {
      both.vertices.row(v0 + i) = (pose * finger.vertices.row(i).transpose()).transpose();
    }
    both.tets.bottomRows(finger.tets.rows()) = finger.tets.array() + static_cast<int>(v0);
  }
  return both;
}

geometry::SurfaceMesh ParallelGripper::finger_surface_of(Jaw jaw) const {
  if (jaw == Jaw::kPositive || second_finger == SecondFinger::kSame) return finger_surface;
  // The reflection x -> -x turns every triangle inside out: two corners swap back.
  geometry::SurfaceMesh mirrored = finger_surface;
  mirrored.vertices.col(0) = -mirrored.vertices.col(0);
  mirrored.triangles.col(1).swap(mirrored.triangles.col(2));
  return mirrored;
}

std::optional<FinRayFinger> ParallelGripper::soft_finger_of(Jaw jaw) const {
  if (!soft_finger || jaw == Jaw::kPositive || second_finger == SecondFinger::kSame) {
    return soft_finger;
  }
  FinRayFinger mirrored = *soft_finger;
  mirrored.mesh.vertices.col(0) = -mirrored.mesh.vertices.col(0);
  mirrored.mesh.tets.col(1).swap(mirrored.mesh.tets.col(2));  // positive again
  return mirrored;
}

namespace {

// How deep, as a fraction of the finger's length, an object must reach between the fingers for
// them to squeeze 50 N before the jaws close (docs/synthesis.md, "Grasp depth"). The solid
// production finger on a 67 mm cylinder: 48-49 N at 0.34-0.91 of its length deep, 27 N with the
// jaws closed at 0.26; the gate keeps a step of margin for narrower objects. The hollow 80 mm
// finger bends away more: 48-52 N at 0.80-0.85, 9-19 N at 0-0.55.
constexpr double kSolidFingerMinGraspDepth = 0.45;
constexpr double kHollowFingerMinGraspDepth = 0.75;

}  // namespace

ParallelGripper make_umi_soft_gripper(const FinRayOptions& options) {
  ParallelGripper gripper;
  gripper.name = "umi_soft";
  gripper.soft_finger = make_fin_ray_finger(options);
  gripper.finger_surface = geometry::boundary_surface(gripper.soft_finger->mesh);
  gripper.min_grasp_depth =
      (options.hollow ? kHollowFingerMinGraspDepth : kSolidFingerMinGraspDepth) * options.length;
  return gripper;
}

ParallelGripper make_rigid_jaw_gripper(const RigidJawOptions& options) {
  ParallelGripper gripper;
  gripper.name = "rigid_jaw";
  gripper.finger_surface =
      geometry::make_box(Eigen::Vector3d(options.width, options.thickness, options.length));
  gripper.finger_surface.vertices.col(1).array() += 0.5 * options.thickness;
  gripper.finger_surface.vertices.col(2).array() += 0.5 * options.length;
  return gripper;
}

}  // namespace grip::grippers
