#include "src/grippers/kinematic_tree.hpp"

#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "src/geometry/mesh_io.hpp"
#include "src/geometry/primitives.hpp"
#include "src/grippers/surface_merge.hpp"

namespace grip::grippers {
namespace {

constexpr int kRoundSegments = 24;  // facets around spheres and cylinders from URDF primitives
constexpr int kRoundRings = 6;

Eigen::Isometry3d to_isometry(const urdf::Pose& pose) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() =
      Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z)
          .normalized()
          .toRotationMatrix();
  t.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return t;
}

std::string quoted(const std::filesystem::path& path) {
  std::string text(1, '\'');
  text += path.string();
  text += '\'';
  return text;
}

bool starts_with(const std::string& text, const std::string& prefix) {
  return text.rfind(prefix, 0) == 0;
}

// Where a URDF mesh file name may point, in the order tried.
std::vector<std::filesystem::path> mesh_candidates(const std::filesystem::path& urdf_dir,
                                                   const std::string& filename) {
  if (starts_with(filename, "file://")) {
    const std::filesystem::path path = filename.substr(7);
    return {path.is_absolute() ? path : urdf_dir / path};
  }
  if (!starts_with(filename, "package://")) {
    const std::filesystem::path path = filename;
    return {path.is_absolute() ? path : urdf_dir / path};
  }
  const std::string rest = filename.substr(10);
  const std::size_t slash = rest.find('/');
  const std::string package = slash == std::string::npos ? rest : rest.substr(0, slash);
  const std::string inside = slash == std::string::npos ? "" : rest.substr(slash + 1);
  std::vector<std::filesystem::path> candidates;
  for (std::filesystem::path folder = urdf_dir;; folder = folder.parent_path()) {
    candidates.push_back(folder / inside);
    candidates.push_back(folder / package / inside);
    if (folder == folder.parent_path() || folder.empty()) break;
  }
  return candidates;
}

class UrdfReader {
 public:
  UrdfReader(const std::filesystem::path& urdf, LinkGeometry geometry)
      : urdf_(urdf),
        urdf_dir_(std::filesystem::absolute(urdf).parent_path()),
        geometry_(geometry) {}

  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error("URDF " + quoted(urdf_) + ": " + what);
  }

  geometry::SurfaceMesh link_surface(const urdf::Link& link) const {
    const bool visual = geometry_ == LinkGeometry::kVisual;
    const bool use_visual = visual ? !link.visual_array.empty() : link.collision_array.empty();
    geometry::SurfaceMesh surface;
    auto add = [&](const urdf::GeometrySharedPtr& shape, const urdf::Pose& origin) {
      if (!shape) return;
      const Eigen::Isometry3d pose = to_isometry(origin);
      append_transformed(surface, shape_surface(link.name, *shape), Eigen::Affine3d(pose));
    };
    if (use_visual) {
      for (const auto& v : link.visual_array) add(v->geometry, v->origin);
    } else {
      for (const auto& c : link.collision_array) add(c->geometry, c->origin);
    }
    return surface;
  }

  KinematicJoint joint(const urdf::Joint& j) const {
    KinematicJoint joint;
    joint.name = j.name;
    joint.origin = to_isometry(j.parent_to_joint_origin_transform);
    switch (j.type) {
      case urdf::Joint::FIXED:
        joint.type = JointType::kFixed;
        return joint;
      case urdf::Joint::REVOLUTE:
        joint.type = JointType::kRevolute;
        break;
      case urdf::Joint::CONTINUOUS:
        joint.type = JointType::kContinuous;
        break;
      case urdf::Joint::PRISMATIC:
        joint.type = JointType::kPrismatic;
        break;
      default:
        fail("joint '" + j.name +
             "' is floating, planar or of unknown type; grip supports fixed, revolute, "
             "continuous and prismatic joints (the hand's base pose is given separately)");
    }
    const Eigen::Vector3d axis(j.axis.x, j.axis.y, j.axis.z);
    if (!(axis.norm() > 0.0)) fail("joint '" + j.name + "' has a zero <axis>");
    joint.axis = axis.normalized();
    if (joint.type == JointType::kContinuous) {
      joint.lower = -std::numeric_limits<double>::infinity();
      joint.upper = std::numeric_limits<double>::infinity();
      return joint;
    }
    if (!j.limits) fail("joint '" + j.name + "' has no <limit>; add lower and upper");
    joint.lower = j.limits->lower;
    joint.upper = j.limits->upper;
    if (!(joint.lower <= joint.upper)) {
      fail("joint '" + j.name + "' has <limit> lower > upper; swap them");
    }
    return joint;
  }

 private:
  geometry::SurfaceMesh shape_surface(const std::string& link, const urdf::Geometry& shape) const {
    switch (shape.type) {
      case urdf::Geometry::BOX: {
        const auto& box = static_cast<const urdf::Box&>(shape);
        return geometry::make_box(Eigen::Vector3d(box.dim.x, box.dim.y, box.dim.z));
      }
      case urdf::Geometry::CYLINDER: {
        const auto& cylinder = static_cast<const urdf::Cylinder&>(shape);
        return geometry::make_cylinder(cylinder.radius, cylinder.length, kRoundSegments);
      }
      case urdf::Geometry::SPHERE: {
        const auto& sphere = static_cast<const urdf::Sphere&>(shape);
        return geometry::make_sphere(sphere.radius, kRoundSegments, kRoundRings);
      }
      case urdf::Geometry::MESH:
        return mesh_surface(link, static_cast<const urdf::Mesh&>(shape));
    }
    fail("link '" + link + "' has a geometry of unknown type");
  }

  geometry::SurfaceMesh mesh_surface(const std::string& link, const urdf::Mesh& mesh) const {
    const std::vector<std::filesystem::path> candidates = mesh_candidates(urdf_dir_, mesh.filename);
    const auto found = std::find_if(candidates.begin(), candidates.end(), [](const auto& path) {
      return std::filesystem::is_regular_file(path);
    });
    if (found == candidates.end()) {
      std::string tried;
      for (std::size_t i = 0; i < candidates.size() && i < 4; ++i) {
        tried += (i ? ", " : "") + quoted(candidates[i]);
      }
      if (candidates.size() > 4) tried += ", ...";
      fail("link '" + link + "': mesh '" + mesh.filename + "' not found (looked for " + tried +
           "); put the mesh there or fix the filename");
    }
    geometry::SurfaceMesh surface;
    try {
      surface = geometry::read_surface_mesh(*found);
    } catch (const std::exception& e) {
      fail("link '" + link + "': " + e.what());
    }
    const Eigen::Vector3d scale(mesh.scale.x, mesh.scale.y, mesh.scale.z);
    if (!(scale.array().abs() > 0.0).all()) fail("link '" + link + "': mesh scale has a zero");
    geometry::SurfaceMesh scaled;
    append_transformed(scaled, surface, Eigen::Affine3d(Eigen::Scaling(scale)));
    return scaled;
  }

  std::filesystem::path urdf_;
  std::filesystem::path urdf_dir_;
  LinkGeometry geometry_;
};

}  // namespace

KinematicTree KinematicTree::from_urdf(const std::filesystem::path& urdf, LinkGeometry geometry) {
  if (!std::filesystem::is_regular_file(urdf)) {
    throw std::runtime_error("URDF " + quoted(urdf) + " not found; check the path");
  }
  const urdf::ModelInterfaceSharedPtr model = urdf::parseURDFFile(urdf.string());
  const UrdfReader reader(urdf, geometry);
  if (!model) {
    reader.fail("not a valid URDF (urdfdom's parser rejected it; its message is printed above)");
  }
  if (!model->getRoot()) reader.fail("has no root link");

  KinematicTree tree;
  tree.name_ = model->getName();
  // Depth first from the root; a joint is numbered just before its child link.
  auto visit = [&](auto& self, const urdf::LinkConstSharedPtr& link, int parent_joint) -> int {
    const int index = static_cast<int>(tree.links_.size());
    tree.links_.push_back({link->name, parent_joint, reader.link_surface(*link)});
    std::vector<urdf::JointSharedPtr> children = link->child_joints;
    std::sort(children.begin(), children.end(),
              [](const auto& a, const auto& b) { return a->name < b->name; });
    for (const urdf::JointSharedPtr& child : children) {
      KinematicJoint joint = reader.joint(*child);
      joint.parent_link = index;
      if (joint.type != JointType::kFixed) {
        joint.dof = static_cast<int>(tree.dof_joints_.size());
        tree.dof_joints_.push_back(static_cast<int>(tree.joints_.size()));
      }
      const int joint_index = static_cast<int>(tree.joints_.size());
      tree.joints_.push_back(joint);
      const int child_link = self(self, model->getLink(child->child_link_name), joint_index);
      tree.joints_[static_cast<std::size_t>(joint_index)].child_link = child_link;
    }
    return index;
  };
  visit(visit, model->getRoot(), -1);

  tree.lower_.resize(tree.dof_count());
  tree.upper_.resize(tree.dof_count());
  for (int d = 0; d < tree.dof_count(); ++d) {
    tree.lower_[d] = tree.dof_joint(d).lower;
    tree.upper_[d] = tree.dof_joint(d).upper;
  }
  return tree;
}

const KinematicJoint& KinematicTree::dof_joint(int dof) const {
  return joints_.at(static_cast<std::size_t>(dof_joints_.at(static_cast<std::size_t>(dof))));
}

int KinematicTree::link_index(const std::string& link) const {
  for (std::size_t i = 0; i < links_.size(); ++i) {
    if (links_[i].name == link) return static_cast<int>(i);
  }
  throw std::out_of_range(name_ + " has no link '" + link + "'");
}

int KinematicTree::dof_index(const std::string& joint) const {
  for (const KinematicJoint& j : joints_) {
    if (j.name == joint && j.dof >= 0) return j.dof;
  }
  throw std::out_of_range(name_ + " has no movable joint '" + joint + "'");
}

bool KinematicTree::within_limits(const Eigen::VectorXd& q) const {
  return q.size() == dof_count() && (q.array() >= lower_.array()).all() &&
         (q.array() <= upper_.array()).all();
}

Eigen::VectorXd KinematicTree::clamp_to_limits(const Eigen::VectorXd& q) const {
  if (q.size() != dof_count()) {
    throw std::invalid_argument(name_ + ": " + std::to_string(q.size()) +
                                " joint values given for " + std::to_string(dof_count()) +
                                " degrees of freedom");
  }
  return q.cwiseMax(lower_).cwiseMin(upper_);
}

std::vector<Eigen::Isometry3d> KinematicTree::link_poses(const Eigen::Isometry3d& base,
                                                         const Eigen::VectorXd& q) const {
  if (q.size() != dof_count()) {
    throw std::invalid_argument(name_ + ": " + std::to_string(q.size()) +
                                " joint values given for " + std::to_string(dof_count()) +
                                " degrees of freedom");
  }
  for (int d = 0; d < dof_count(); ++d) {
    if (!(q[d] >= lower_[d] && q[d] <= upper_[d])) {
      throw std::invalid_argument(name_ + ": joint '" + dof_joint(d).name + "' value " +
                                  std::to_string(q[d]) + " is outside its limits [" +
                                  std::to_string(lower_[d]) + ", " + std::to_string(upper_[d]) +
                                  "]");
    }
  }
  std::vector<Eigen::Isometry3d> poses(links_.size(), base);
  for (const KinematicJoint& joint : joints_) {  // parents come before their children
    Eigen::Isometry3d frame = poses[static_cast<std::size_t>(joint.parent_link)] * joint.origin;
    if (joint.type == JointType::kRevolute || joint.type == JointType::kContinuous) {
      frame.rotate(Eigen::AngleAxisd(q[joint.dof], joint.axis));
    } else if (joint.type == JointType::kPrismatic) {
      frame.translate(q[joint.dof] * joint.axis);
    }
    poses[static_cast<std::size_t>(joint.child_link)] = frame;
  }
  return poses;
}

Eigen::Matrix<double, 6, Eigen::Dynamic> KinematicTree::point_jacobian(
    const std::vector<Eigen::Isometry3d>& poses, int link, const Eigen::Vector3d& point) const {
  Eigen::Matrix<double, 6, Eigen::Dynamic> jacobian =
      Eigen::Matrix<double, 6, Eigen::Dynamic>::Zero(6, dof_count());
  const Eigen::Vector3d p = poses.at(static_cast<std::size_t>(link)) * point;
  for (int j = links_.at(static_cast<std::size_t>(link)).parent_joint; j >= 0;
       j = links_[static_cast<std::size_t>(joints_[static_cast<std::size_t>(j)].parent_link)]
               .parent_joint) {
    const KinematicJoint& joint = joints_[static_cast<std::size_t>(j)];
    if (joint.dof < 0) continue;
    const Eigen::Isometry3d frame =
        poses[static_cast<std::size_t>(joint.parent_link)] * joint.origin;
    const Eigen::Vector3d axis = frame.linear() * joint.axis;
    if (joint.type == JointType::kPrismatic) {
      jacobian.col(joint.dof) << axis, Eigen::Vector3d::Zero();
    } else {
      jacobian.col(joint.dof) << axis.cross(p - frame.translation()), axis;
    }
  }
  return jacobian;
}

geometry::SurfaceMesh KinematicTree::posed_surface(
    const std::vector<Eigen::Isometry3d>& poses) const {
  geometry::SurfaceMesh mesh;
  for (std::size_t i = 0; i < links_.size(); ++i) {
    append_transformed(mesh, links_[i].surface, Eigen::Affine3d(poses.at(i)));
  }
  return mesh;
}

}  // namespace grip::grippers
