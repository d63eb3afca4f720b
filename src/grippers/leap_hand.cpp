#include "src/grippers/leap_hand.hpp"

#include <array>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "src/geometry/mesh_io.hpp"
#include "src/geometry/primitives.hpp"
#include "src/grippers/hand_points.hpp"
#include "src/grippers/number_text.hpp"

namespace grip::grippers {
namespace {

// Link dimensions (m).
constexpr double kPalmLength = 0.10;     // x
constexpr double kPalmWidth = 0.09;      // y
constexpr double kPalmThickness = 0.03;  // z, grasping face at z = 0
constexpr double kFingerSpacing = 0.03;  // between index, middle and ring (y)
constexpr double kJointDepth = -0.015;   // finger joints at mid-thickness of the palm
constexpr double kThumbBaseX = 0.03;     // thumb base along the palm's -y side
constexpr double kKnuckleLength = 0.015;
constexpr double kProximalLength = 0.040;
constexpr double kThumbProximalLength = 0.035;
constexpr double kIntermediateLength = 0.030;
constexpr double kDistalLength = 0.030;
constexpr double kLinkRadius = 0.0095;  // capsule radius of the phalanges
constexpr double kJointGap = 0.001;     // clearance between a capsule and its joint
constexpr int kCapsuleSegments = 24;    // multiple of 12: contact points sit on mesh edges
constexpr int kCapsuleRings = 4;

// The real LEAP Hand's limits (rad): abduction, MCP, PIP, DIP of a finger; the thumb's four.
constexpr std::array<std::array<double, 2>, 4> kFingerLimits{
    {{-1.047, 1.047}, {-0.314, 2.23}, {-0.506, 1.885}, {-0.366, 2.042}}};
constexpr std::array<std::array<double, 2>, 4> kThumbLimits{
    {{-0.349, 2.094}, {-0.47, 2.443}, {-1.20, 1.90}, {-1.34, 1.88}}};
constexpr double kEffort = 0.95;    // N m, Dynamixel XC330 class
constexpr double kVelocity = 8.48;  // rad/s

struct LinkSpec {
  std::string name;
  std::string mesh;  // file stem under meshes/
};

struct JointSpec {
  std::string name;
  std::string parent;
  std::string child;
  Eigen::Vector3d xyz;
  Eigen::Vector3d rpy;
  Eigen::Vector3d axis;
  double lower;
  double upper;
};

struct MeshSpec {
  std::string stem;
  geometry::SurfaceMesh mesh;
};

struct HandSpec {
  std::string name;
  std::vector<MeshSpec> meshes;
  std::vector<LinkSpec> links;
  std::vector<JointSpec> joints;
  HandPoints points;
};

// A phalanx: capsule along +x from kJointGap to `end`.
geometry::SurfaceMesh phalanx(double end) {
  geometry::SurfaceMesh mesh =
      geometry::make_capsule(kLinkRadius, end - kJointGap, kCapsuleSegments, kCapsuleRings);
  mesh.vertices.col(0).array() += kJointGap;
  return mesh;
}

geometry::SurfaceMesh shifted_box(const Eigen::Vector3d& size, const Eigen::Vector3d& center) {
  geometry::SurfaceMesh mesh = geometry::make_box(size);
  mesh.vertices.rowwise() += center.transpose();
  return mesh;
}

// 15 contact candidates on a distal link's pad (+z side): 4 meridians 30 degrees apart at 3
// stations of the straight part, and 3 on the tip cap's +z meridian. All lie on mesh edges or
// vertices of the capsule.
void add_fingertip_contacts(const std::string& link, HandPoints& points) {
  const double start = kJointGap + kLinkRadius;    // straight part of the capsule
  const double end = kDistalLength - kLinkRadius;  // centre of the tip cap
  for (const double x : {start, 0.5 * (start + end), end}) {
    for (const double degrees : {-45.0, -15.0, 15.0, 45.0}) {  // from +z towards -y
      const double a = degrees * std::numbers::pi / 180.0;
      const Eigen::Vector3d normal(0.0, -std::sin(a), std::cos(a));
      points.contacts.push_back(
          {link, Eigen::Vector3d(x, 0.0, 0.0) + kLinkRadius * normal, normal});
    }
  }
  for (int ring = 1; ring < kCapsuleRings; ++ring) {  // latitudes 22.5, 45, 67.5 degrees
    const double a = 0.5 * std::numbers::pi * ring / kCapsuleRings;
    const Eigen::Vector3d normal(std::sin(a), 0.0, std::cos(a));
    points.contacts.push_back(
        {link, Eigen::Vector3d(end, 0.0, 0.0) + kLinkRadius * normal, normal});
  }
}

// Keypoint spheres filling a phalanx: at both ends and the middle of its straight part.
void add_phalanx_keypoints(const std::string& link, double end, HandPoints& points) {
  const double first = kJointGap + kLinkRadius;
  const double last = end - kLinkRadius;
  for (const double x : {first, 0.5 * (first + last), last}) {
    points.keypoints.push_back({link, Eigen::Vector3d(x, 0.0, 0.0), kLinkRadius});
  }
}

HandSpec right_hand() {
  HandSpec hand;
  hand.name = "leap_right";
  const Eigen::Vector3d knuckle_size(kKnuckleLength - 2.0 * kJointGap, 0.018, 0.018);
  const Eigen::Vector3d knuckle_center(0.5 * kKnuckleLength, 0.0, 0.0);
  hand.meshes = {
      {"palm", shifted_box(Eigen::Vector3d(kPalmLength, kPalmWidth, kPalmThickness),
                           Eigen::Vector3d(0.5 * kPalmLength, 0.0, -0.5 * kPalmThickness))},
      {"knuckle", shifted_box(knuckle_size, knuckle_center)},
      {"proximal", phalanx(kProximalLength)},
      {"thumb_proximal", phalanx(kThumbProximalLength)},
      {"intermediate", phalanx(kIntermediateLength)},
      {"distal", phalanx(kDistalLength)}};
  hand.links.push_back({"palm", "palm"});
  for (int x = 0; x < 3; ++x) {
    for (int y = 0; y < 3; ++y) {
      hand.points.keypoints.push_back(
          {"palm", Eigen::Vector3d(0.02 + 0.03 * x, -0.03 + 0.03 * y, -0.5 * kPalmThickness),
           0.015});
    }
  }
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  const Eigen::Vector3d flex(0.0, -1.0, 0.0);  // curls +x towards +z
  struct Finger {
    std::string name;
    Eigen::Vector3d base;
    Eigen::Vector3d base_rpy;
    Eigen::Vector3d first_axis;
    std::array<std::string, 4> joints;
    std::array<std::array<double, 2>, 4> limits;
    double proximal_length;
  };
  const std::vector<Finger> fingers = {
      {"index",
       {kPalmLength, -kFingerSpacing, kJointDepth},
       zero,
       Eigen::Vector3d::UnitZ(),
       {"abd", "mcp", "pip", "dip"},
       kFingerLimits,
       kProximalLength},
      {"middle",
       {kPalmLength, 0.0, kJointDepth},
       zero,
       Eigen::Vector3d::UnitZ(),
       {"abd", "mcp", "pip", "dip"},
       kFingerLimits,
       kProximalLength},
      {"ring",
       {kPalmLength, kFingerSpacing, kJointDepth},
       zero,
       Eigen::Vector3d::UnitZ(),
       {"abd", "mcp", "pip", "dip"},
       kFingerLimits,
       kProximalLength},
      // The thumb leaves the palm's -y side pointing along -y and first turns about its own
      // axis (turning its pad from the palm normal towards the fingers), then flexes.
      {"thumb",
       {kThumbBaseX, -0.5 * kPalmWidth, kJointDepth},
       {0.0, 0.0, -0.5 * std::numbers::pi},
       -Eigen::Vector3d::UnitX(),
       {"rot", "abd", "mcp", "ip"},
       kThumbLimits,
       kThumbProximalLength}};
  for (const Finger& f : fingers) {
    const std::array<std::string, 4> links = {f.name + "_knuckle", f.name + "_proximal",
                                              f.name + "_intermediate", f.name + "_distal"};
    const std::array<double, 4> offsets = {0.0, kKnuckleLength, f.proximal_length,
                                           kIntermediateLength};
    for (int k = 0; k < 4; ++k) {
      const std::string parent = k == 0 ? "palm" : links[static_cast<std::size_t>(k - 1)];
      hand.joints.push_back(
          {f.name + "_" + f.joints[static_cast<std::size_t>(k)], parent,
           links[static_cast<std::size_t>(k)],
           k == 0 ? f.base : Eigen::Vector3d(offsets[static_cast<std::size_t>(k)], 0.0, 0.0),
           k == 0 ? f.base_rpy : zero, k == 0 ? f.first_axis : flex,
           f.limits[static_cast<std::size_t>(k)][0], f.limits[static_cast<std::size_t>(k)][1]});
    }
    hand.links.push_back({links[0], "knuckle"});
    hand.links.push_back({links[1], f.name == "thumb" ? "thumb_proximal" : "proximal"});
    hand.links.push_back({links[2], "intermediate"});
    hand.links.push_back({links[3], "distal"});
    hand.points.keypoints.push_back({links[0], knuckle_center, 0.5 * knuckle_size.minCoeff()});
    add_phalanx_keypoints(links[1], f.proximal_length, hand.points);
    add_phalanx_keypoints(links[2], kIntermediateLength, hand.points);
    add_phalanx_keypoints(links[3], kDistalLength, hand.points);
    add_fingertip_contacts(links[3], hand.points);
  }
  return hand;
}

// Mirror through the x-z plane: M = diag(1, -1, 1). A joint origin R becomes M R M, which in
// roll-pitch-yaw is (-roll, pitch, -yaw); an axis a becomes -M a, so that M R(a, q) M = R(-M a, q)
// and equal joint values give mirrored poses.
HandSpec mirrored(HandSpec hand, const std::string& name) {
  hand.name = name;
  const Eigen::Vector3d m(1.0, -1.0, 1.0);
  for (MeshSpec& mesh : hand.meshes) {
    mesh.mesh.vertices.col(1) *= -1.0;
    mesh.mesh.triangles.col(1).swap(mesh.mesh.triangles.col(2));
  }
  for (JointSpec& joint : hand.joints) {
    joint.xyz = joint.xyz.cwiseProduct(m);
    joint.rpy = Eigen::Vector3d(-joint.rpy.x(), joint.rpy.y(), -joint.rpy.z());
    joint.axis = -joint.axis.cwiseProduct(m);
  }
  for (ContactCandidate& c : hand.points.contacts) {
    c.position = c.position.cwiseProduct(m);
    c.normal = c.normal.cwiseProduct(m);
  }
  for (PenetrationSphere& s : hand.points.keypoints) s.center = s.center.cwiseProduct(m);
  return hand;
}

std::string triple(const Eigen::Vector3d& v) {
  return number_text(v.x()) + " " + number_text(v.y()) + " " + number_text(v.z());
}

std::string urdf_text(const HandSpec& hand) {
  std::ostringstream out;
  out << "<?xml version=\"1.0\"?>\n"
      << "<!-- " << hand.name
      << ": LEAP-style 16-DoF hand written by grip (src/grippers/leap_hand.cpp); regenerate\n"
      << "     with `grip asset gallery` (docs/assets.md). Joint limits are the real LEAP "
         "Hand's; link\n"
      << "     geometry is grip's own. Frame: +x wrist to fingers, +z out of the palm. -->\n"
      << "<robot name=\"" << hand.name << "\">\n";
  for (const LinkSpec& link : hand.links) {
    const std::string geometry =
        "      <geometry><mesh filename=\"meshes/" + link.mesh + ".obj\"/></geometry>\n";
    out << "  <link name=\"" << link.name << "\">\n"
        << "    <visual>\n      <origin xyz=\"0 0 0\" rpy=\"0 0 0\"/>\n"
        << geometry << "    </visual>\n"
        << "    <collision>\n      <origin xyz=\"0 0 0\" rpy=\"0 0 0\"/>\n"
        << geometry << "    </collision>\n  </link>\n";
  }
  for (const JointSpec& joint : hand.joints) {
    out << "  <joint name=\"" << joint.name << "\" type=\"revolute\">\n"
        << "    <parent link=\"" << joint.parent << "\"/>\n"
        << "    <child link=\"" << joint.child << "\"/>\n"
        << "    <origin xyz=\"" << triple(joint.xyz) << "\" rpy=\"" << triple(joint.rpy) << "\"/>\n"
        << "    <axis xyz=\"" << triple(joint.axis) << "\"/>\n"
        << "    <limit lower=\"" << number_text(joint.lower) << "\" upper=\""
        << number_text(joint.upper) << "\" effort=\"" << number_text(kEffort) << "\" velocity=\""
        << number_text(kVelocity) << "\"/>\n"
        << "  </joint>\n";
  }
  out << "</robot>\n";
  return out.str();
}

void write_text(const std::filesystem::path& file, const std::string& text) {
  std::ofstream out(file);
  out << text;
  out.close();
  if (!out) {
    throw std::runtime_error("cannot write '" + file.string() + "': " + std::strerror(errno));
  }
}

}  // namespace

LeapHandFiles write_leap_hand(const std::filesystem::path& folder, HandSide side) {
  const HandSpec right = right_hand();
  const HandSpec hand = side == HandSide::kRight ? right : mirrored(right, "leap_left");
  std::filesystem::create_directories(folder / "meshes");
  for (const MeshSpec& mesh : hand.meshes) {
    geometry::write_obj(folder / "meshes" / (mesh.stem + ".obj"), mesh.mesh);
  }
  const LeapHandFiles files{folder / (hand.name + ".urdf"), folder / "hand_points.toml"};
  write_text(files.urdf, urdf_text(hand));
  write_hand_points(files.points, hand.points,
                    hand.name +
                        ": contact candidates (15 per fingertip; position and outward\n"
                        "normal in the link frame, m) and self-penetration keypoints\n"
                        "(spheres in link frames, m). Written by grip; see docs/assets.md.");
  return files;
}

std::filesystem::path gripper_asset_dir() {
  if (const char* dir = std::getenv("GRIP_ASSET_DIR"); dir != nullptr && *dir != '\0') {
    return std::filesystem::path(dir) / "grippers";
  }
  return std::filesystem::path(GRIP_SOURCE_ASSET_DIR) / "grippers";
}

LeapHandFiles shipped_leap_hand(HandSide side) {
  const std::string name = side == HandSide::kRight ? "leap_right" : "leap_left";
  const std::filesystem::path folder = gripper_asset_dir() / name;
  return {folder / (name + ".urdf"), folder / "hand_points.toml"};
}

}  // namespace grip::grippers
