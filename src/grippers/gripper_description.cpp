#include "src/grippers/gripper_description.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "src/config/config.hpp"
#include "src/geometry/boundary_surface.hpp"
#include "src/geometry/tet_mesh_io.hpp"
#include "src/grippers/gripper_registry.hpp"
#include "src/grippers/number_text.hpp"

namespace grip::grippers {
namespace {

// The widest stroke a description may give (m): wider, the value is in millimetres.
constexpr double kMaxDescribedOpening = 0.5;

Eigen::Vector3d unit_axis(const config::Table& table, std::string_view key) {
  const std::array<double, 3> a = table.vec3(key);
  const Eigen::Vector3d axis(a[0], a[1], a[2]);
  const double length = axis.stableNorm();  // finite for any finite components
  if (!(length > 0.0)) table.fail(key, "must be a direction, not the zero vector");
  return axis / length;
}

FinRayMaterial read_material(const config::Table& finger) {
  const config::Table m = finger.table("material");
  m.allow({"youngs_modulus", "poisson_ratio", "density", "friction", "damping"});
  FinRayMaterial material;
  material.youngs_modulus = m.number("youngs_modulus");
  if (!(material.youngs_modulus > 0.0)) m.fail("youngs_modulus", "must be positive (Pa)");
  material.poisson_ratio = m.number("poisson_ratio");
  if (!(material.poisson_ratio > -1.0 && material.poisson_ratio < 0.5)) {
    m.fail("poisson_ratio", "must lie in (-1, 0.5)");
  }
  material.density = m.number("density");
  if (!(material.density > 0.0)) m.fail("density", "must be positive (kg/m^3)");
  material.friction = m.number("friction");
  if (!(material.friction >= 0.0)) m.fail("friction", "must be zero or positive");
  material.damping = m.number_or("damping", material.damping);
  if (!(material.damping >= 0.0)) m.fail("damping", "must be zero or positive (s)");
  return material;
}

// The mesh turned into the finger frame: y along -closing (the contact face, the side that
// leads as the jaws close, on y = 0), z along the tip axis from the mount end (z = 0), x = y x z
// (a rotation, so the tets keep their orientation) centred on 0.
geometry::TetMesh to_finger_frame(geometry::TetMesh mesh, double scale,
                                  const Eigen::Vector3d& closing, const Eigen::Vector3d& tip) {
  Eigen::Matrix3d rows;
  rows.row(1) = -closing.transpose();
  rows.row(2) = tip.transpose();
  rows.row(0) = rows.row(1).cross(rows.row(2));
  mesh.vertices = (scale * mesh.vertices) * rows.transpose();
  const Eigen::RowVector3d lower = mesh.vertices.colwise().minCoeff();
  const Eigen::RowVector3d upper = mesh.vertices.colwise().maxCoeff();
  const Eigen::RowVector3d shift(-0.5 * (lower.x() + upper.x()), -lower.y(), -lower.z());
  mesh.vertices.rowwise() += shift;
  return mesh;
}

// The pinned vertices span a plane when some three of them are off one line.
bool spans_a_plane(const geometry::Vertices& v, const std::vector<int>& pinned) {
  if (pinned.size() < 3) return false;
  const Eigen::Vector3d a = v.row(pinned[0]);
  const auto far = std::max_element(pinned.begin(), pinned.end(), [&](int i, int j) {
    return (Eigen::Vector3d(v.row(i)) - a).norm() < (Eigen::Vector3d(v.row(j)) - a).norm();
  });
  const Eigen::Vector3d b = Eigen::Vector3d(v.row(*far)) - a;
  const double size = b.norm();
  if (!(size > 0.0)) return false;
  return std::any_of(pinned.begin(), pinned.end(), [&](int i) {
    return b.cross(Eigen::Vector3d(v.row(i)) - a).norm() > 1e-3 * size * size;
  });
}

// The vertices [finger.mount] pins: those within `depth` of the mount face (z = 0 in the finger
// frame), or those inside the box `lower`-`upper` of the mesh file's coordinates.
std::vector<int> mount_vertices(const config::Table& finger, const geometry::TetMesh& file_mesh,
                                const geometry::TetMesh& mesh) {
  const config::Table mount = finger.table("mount");
  mount.allow({"depth", "lower", "upper"});
  const bool plane = mount.has("depth");
  if (plane == (mount.has("lower") || mount.has("upper"))) {
    mount.fail(plane ? "depth" : "lower",
               "the mount is either a depth (the plane) or a box (lower and upper), one of them");
  }
  std::vector<int> pinned;
  std::string key;
  if (plane) {
    key = "depth";
    const double depth = mount.number("depth");
    if (!(depth > 0.0)) mount.fail("depth", "must be positive (m)");
    // A vertex meant to lie on the plane may lie a rounding above it after scaling.
    const double plane_z = depth * (1.0 + 1e-9);
    for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
      if (mesh.vertices(v, 2) <= plane_z) pinned.push_back(static_cast<int>(v));
    }
  } else {
    key = "lower";
    const std::array<double, 3> l = mount.vec3("lower");
    const std::array<double, 3> u = mount.vec3("upper");
    const Eigen::RowVector3d lower(l[0], l[1], l[2]);
    const Eigen::RowVector3d upper(u[0], u[1], u[2]);
    if (!(lower.array() < upper.array()).all()) {
      mount.fail("upper", "must exceed lower in x, y and z");
    }
    for (Eigen::Index v = 0; v < file_mesh.vertices.rows(); ++v) {
      const Eigen::RowVector3d p = file_mesh.vertices.row(v);
      if ((p.array() >= lower.array()).all() && (p.array() <= upper.array()).all()) {
        pinned.push_back(static_cast<int>(v));
      }
    }
  }
  if (pinned.empty()) {
    mount.fail(key,
               "selects no vertex of the finger; the jaw would hold nothing (a depth is in "
               "metres from the finger's end opposite its tip; a box in the mesh file's "
               "coordinates)");
  }
  if (pinned.size() == static_cast<std::size_t>(mesh.vertices.rows())) {
    mount.fail(key, "pins every vertex of the finger, which could then not bend: pin its base");
  }
  if (!spans_a_plane(mesh.vertices, pinned)) {
    mount.fail(key, "pins " + std::to_string(pinned.size()) +
                        " vertices on one line or point; the finger would swing about them: pin "
                        "a face of it");
  }
  return pinned;
}

}  // namespace

bool is_gripper_description(const std::filesystem::path& text) {
  return text.extension() == ".toml";
}

ParallelGripper load_gripper_description(const std::filesystem::path& file) {
  const config::Document document = config::Document::load(file);
  const config::Table root = document.root();
  root.allow({"gripper", "finger"});

  const config::Table head = root.table("gripper");
  head.allow({"name", "opening", "grasp_depth", "second_finger"});
  ParallelGripper gripper;
  gripper.name = head.string("name");
  if (gripper.name.empty() || gripper.name.find_first_of(" \t/") != std::string::npos) {
    head.fail("name",
              "must be a non-empty word without '/' or spaces (the dataset names the "
              "gripper by it)");
  }
  if (find_gripper_type(gripper.name)) {
    head.fail("name", "is \"" + gripper.name + "\", a built-in gripper's; name yours otherwise");
  }
  const std::vector<double> opening = head.numbers("opening");
  if (opening.size() != 2 || !(opening[0] >= 0.0 && opening[0] < opening[1])) {
    head.fail("opening", "must be [least, largest] jaw openings in metres, 0 <= least < largest");
  }
  if (opening[1] > kMaxDescribedOpening) {
    head.fail("opening", "opens to " + number_text(opening[1]) + " m, more than " +
                             number_text(kMaxDescribedOpening) +
                             " m: is it in millimetres? "
                             "Give metres");
  }
  gripper.min_opening = opening[0];
  gripper.max_opening = opening[1];
  if (head.choice_or("second_finger", {"same", "mirrored"}, "same") == "mirrored") {
    gripper.second_finger = SecondFinger::kMirrored;
  }

  const config::Table finger = root.table("finger");
  finger.allow({"mesh", "scale", "closing_axis", "tip_axis", "mount", "material"});
  const std::filesystem::path mesh_file = file.parent_path() / finger.string("mesh");
  if (!geometry::is_tet_mesh_file(mesh_file)) {
    finger.fail("mesh", "names '" + mesh_file.string() +
                            "', not a tet mesh: give a .vtk, .msh or .mesh file");
  }
  const double scale = finger.number_or("scale", 1.0);
  if (!(scale > 0.0)) finger.fail("scale", "must be positive (0.001 for a mesh in millimetres)");
  const Eigen::Vector3d closing = unit_axis(finger, "closing_axis");
  const Eigen::Vector3d tip = unit_axis(finger, "tip_axis");
  if (std::abs(closing.dot(tip)) > 1e-3) {
    finger.fail("tip_axis", "must be perpendicular to closing_axis");
  }

  geometry::TetMesh file_mesh;
  FinRayFinger soft;
  try {
    file_mesh = geometry::read_tet_mesh(mesh_file);
    soft.mesh = to_finger_frame(file_mesh, scale, closing, tip);
    geometry::check_soft_body_mesh(soft.mesh, mesh_file.string(), kMaxDescribedFingerSize);
  } catch (const std::runtime_error& e) {
    // An empty mesh (the file was not read) has no size.
    const double size =
        soft.mesh.vertices.rows() == 0
            ? kMinDescribedFingerSize
            : (soft.mesh.vertices.colwise().maxCoeff() - soft.mesh.vertices.colwise().minCoeff())
                  .norm();
    if (size < kMinDescribedFingerSize) {
      finger.fail("scale", "makes the finger " + number_text(size) + " m across, smaller than " +
                               number_text(kMinDescribedFingerSize) +
                               " m: give the scale that turns the mesh's units into metres");
    }
    finger.fail("mesh", std::string("names a finger grip cannot simulate: ") + e.what());
  }
  soft.mount_vertices = mount_vertices(finger, file_mesh, soft.mesh);
  soft.material = read_material(finger);
  const double length = soft.mesh.vertices.col(2).maxCoeff();

  gripper.min_grasp_depth = head.number_or("grasp_depth", 0.0);
  if (!(gripper.min_grasp_depth >= 0.0 && gripper.min_grasp_depth < length)) {
    head.fail("grasp_depth", "must lie in [0, " + number_text(length) +
                                 ") m: from the tips, less than the finger's length");
  }
  gripper.finger_surface = geometry::boundary_surface(soft.mesh);
  gripper.soft_finger = std::move(soft);
  return gripper;
}

}  // namespace grip::grippers
