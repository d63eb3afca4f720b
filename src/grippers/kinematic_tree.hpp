#pragma once
// A robot hand (or any fixed-base tree of links) loaded from URDF with its link meshes:
// joint limits, forward kinematics and geometric Jacobians of points on links.
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "src/geometry/mesh.hpp"

namespace grip::grippers {

enum class JointType { kFixed, kRevolute, kContinuous, kPrismatic };

struct KinematicJoint {
  std::string name;
  JointType type = JointType::kFixed;
  int parent_link = -1;
  int child_link = -1;
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();  // child frame at q = 0, in parent
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();           // unit, in the joint frame
  double lower = 0.0;                                        // rad or m; -inf if continuous
  double upper = 0.0;
  int dof = -1;  // index into the joint vector q; -1 for a fixed joint
};

struct KinematicLink {
  std::string name;
  int parent_joint = -1;          // -1 for the root
  geometry::SurfaceMesh surface;  // all geometry elements of the link, in the link frame
};

// Which URDF geometry becomes the link surface. GRIP collides with the hands' visual meshes;
// a link without the chosen kind falls back to the other.
enum class LinkGeometry { kVisual, kCollision };

class KinematicTree {
 public:
  // Parses `urdf` with urdfdom and reads every link mesh (OBJ, STL, PLY, OFF). Mesh file names
  // are resolved against the URDF's folder; "package://NAME/rest" is looked up as rest, then
  // as NAME/rest, in the URDF's folder and each folder above it; "file://" is stripped.
  // Links are numbered depth first from the root and joints with them (children in name
  // order, as urdfdom gives them); the degrees of freedom follow the same order. Throws
  // std::runtime_error naming the URDF file (and link, and mesh) on any problem.
  static KinematicTree from_urdf(const std::filesystem::path& urdf,
                                 LinkGeometry geometry = LinkGeometry::kVisual);

  const std::string& name() const { return name_; }
  int dof_count() const { return static_cast<int>(dof_joints_.size()); }
  const std::vector<KinematicLink>& links() const { return links_; }
  const std::vector<KinematicJoint>& joints() const { return joints_; }
  // The joint that moves degree of freedom `dof`.
  const KinematicJoint& dof_joint(int dof) const;
  int link_index(const std::string& link) const;  // throws std::out_of_range if unknown
  int dof_index(const std::string& joint) const;  // throws std::out_of_range if unknown or fixed

  const Eigen::VectorXd& lower_limits() const { return lower_; }
  const Eigen::VectorXd& upper_limits() const { return upper_; }
  bool within_limits(const Eigen::VectorXd& q) const;
  Eigen::VectorXd clamp_to_limits(const Eigen::VectorXd& q) const;

  // World pose of every link for joint values q (size dof_count(), within the limits; throws
  // std::invalid_argument naming the joint otherwise) and the root pose `base`.
  std::vector<Eigen::Isometry3d> link_poses(const Eigen::Isometry3d& base,
                                            const Eigen::VectorXd& q) const;

  // Geometric Jacobian (6 x dof_count) of the point `point` (link frame) on link `link`, at
  // the configuration whose link_poses are `poses`: rows 0-2 map q-dot to the point's world
  // velocity, rows 3-5 to the link's world angular velocity. The base is held fixed.
  Eigen::Matrix<double, 6, Eigen::Dynamic> point_jacobian(
      const std::vector<Eigen::Isometry3d>& poses, int link, const Eigen::Vector3d& point) const;

  // Every link surface placed at `poses`, gathered into one mesh in the world frame.
  geometry::SurfaceMesh posed_surface(const std::vector<Eigen::Isometry3d>& poses) const;

 private:
  std::string name_;
  std::vector<KinematicLink> links_;
  std::vector<KinematicJoint> joints_;
  std::vector<int> dof_joints_;
  Eigen::VectorXd lower_;
  Eigen::VectorXd upper_;
};

}  // namespace grip::grippers
