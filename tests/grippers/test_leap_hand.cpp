#include "src/grippers/leap_hand.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>

#include "src/geometry/mesh_io.hpp"
#include "src/grippers/hand_model.hpp"
#include "src/grippers/hand_points.hpp"

namespace grip::grippers {
namespace {

std::filesystem::path scratch_dir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("grip_leap_" + name + "_" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

std::string file_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The shipped hands are exactly what the generator writes: the URDF and points byte for byte,
// the meshes vertex for vertex.
TEST(GrippersLeapHand, ShippedAssetsAreTheGeneratorsOutput) {
  for (const HandSide side : {HandSide::kRight, HandSide::kLeft}) {
    const LeapHandFiles shipped = shipped_leap_hand(side);
    const LeapHandFiles fresh = write_leap_hand(scratch_dir("regen"), side);
    EXPECT_EQ(file_text(fresh.urdf), file_text(shipped.urdf)) << shipped.urdf;
    EXPECT_EQ(file_text(fresh.points), file_text(shipped.points)) << shipped.points;
    const std::filesystem::path meshes = fresh.urdf.parent_path() / "meshes";
    int count = 0;
    for (const auto& entry : std::filesystem::directory_iterator(meshes)) {
      const std::filesystem::path other =
          shipped.urdf.parent_path() / "meshes" / entry.path().filename();
      const geometry::SurfaceMesh a = geometry::read_surface_mesh(entry.path());
      const geometry::SurfaceMesh b = geometry::read_surface_mesh(other);
      EXPECT_EQ(a.vertices, b.vertices) << other;
      EXPECT_EQ(a.triangles, b.triangles) << other;
      ++count;
    }
    EXPECT_EQ(count, 6);
  }
}

class GrippersShippedHand : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const LeapHandFiles files = shipped_leap_hand(HandSide::kRight);
    hand_ = new HandModel(load_hand_model(files.urdf, files.points));
  }
  static void TearDownTestSuite() { delete hand_; }
  static HandModel* hand_;
};
HandModel* GrippersShippedHand::hand_ = nullptr;

TEST_F(GrippersShippedHand, FifteenContactCandidatesPerFingertipOnThePad) {
  std::map<std::string, int> per_link;
  for (const ContactCandidate& c : hand_->points.contacts) ++per_link[c.link];
  EXPECT_EQ(
      per_link,
      (std::map<std::string, int>{
          {"index_distal", 15}, {"middle_distal", 15}, {"ring_distal", 15}, {"thumb_distal", 15}}));
  for (const ContactCandidate& c : hand_->points.contacts) {
    EXPECT_NEAR(c.normal.norm(), 1.0, 1e-12);
    EXPECT_GT(c.normal.z(), 0.0) << "pads face +z of the link";
  }
}

// Every candidate lies on its link's surface mesh (a vertex or on an edge of it), and its
// normal points away from the link's axis: the capsule's outward normal.
TEST_F(GrippersShippedHand, ContactCandidatesLieOnTheLinkSurfaceWithOutwardNormals) {
  for (const ContactCandidate& c : hand_->points.contacts) {
    const auto& mesh =
        hand_->kinematics.links()[static_cast<std::size_t>(hand_->kinematics.link_index(c.link))]
            .surface;
    double nearest = 1.0;
    for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) {
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d a = mesh.vertices.row(mesh.triangles(t, k)).transpose();
        const Eigen::Vector3d b = mesh.vertices.row(mesh.triangles(t, (k + 1) % 3)).transpose();
        const double s = std::clamp((c.position - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
        nearest = std::min(nearest, (a + s * (b - a) - c.position).norm());
      }
    }
    EXPECT_LT(nearest, 1e-12) << c.link << " " << c.position.transpose();
    // Along the normal, a little way in is inside the capsule (closer to the axis segment than
    // its radius) and a little way out is outside.
    auto axis_distance = [](const Eigen::Vector3d& p) {
      const double x = std::clamp(p.x(), 0.001 + 0.0095, 0.030 - 0.0095);
      return (p - Eigen::Vector3d(x, 0.0, 0.0)).norm();
    };
    EXPECT_NEAR(axis_distance(c.position), 0.0095, 1e-12);
    EXPECT_LT(axis_distance(c.position - 1e-4 * c.normal), 0.0095);
    EXPECT_GT(axis_distance(c.position + 1e-4 * c.normal), 0.0095);
  }
}

TEST_F(GrippersShippedHand, EveryLinkHasKeypointSpheresInsideIt) {
  std::map<std::string, int> per_link;
  for (const PenetrationSphere& s : hand_->points.keypoints) {
    ++per_link[s.link];
    const auto& mesh =
        hand_->kinematics.links()[static_cast<std::size_t>(hand_->kinematics.link_index(s.link))]
            .surface;
    const Eigen::Vector3d low = mesh.vertices.colwise().minCoeff().transpose();
    const Eigen::Vector3d high = mesh.vertices.colwise().maxCoeff().transpose();
    EXPECT_TRUE((s.center.array() > low.array()).all() && (s.center.array() < high.array()).all())
        << s.link;
    EXPECT_LE(s.radius, 0.5 * (high - low).minCoeff() + 1e-12) << s.link;
  }
  EXPECT_EQ(per_link.size(), hand_->kinematics.links().size());
}

TEST(GrippersHandPoints, RoundTripIsExact) {
  HandPoints points;
  points.contacts.push_back(
      {"tip", Eigen::Vector3d(0.1, -2.5e-5, 1.0 / 3.0), Eigen::Vector3d(0.6, 0.0, 0.8)});
  points.keypoints.push_back({"palm", Eigen::Vector3d(-0.0, 1e-9, 7.0), 0.015});
  const std::filesystem::path file = scratch_dir("roundtrip") / "points.toml";
  write_hand_points(file, points, "two lines\nof comment");
  const HandPoints back = read_hand_points(file);
  ASSERT_EQ(back.contacts.size(), 1u);
  ASSERT_EQ(back.keypoints.size(), 1u);
  EXPECT_EQ(back.contacts[0].link, "tip");
  EXPECT_EQ(back.contacts[0].position, points.contacts[0].position);
  EXPECT_EQ(back.contacts[0].normal, points.contacts[0].normal);
  EXPECT_EQ(back.keypoints[0].center, points.keypoints[0].center);
  EXPECT_EQ(back.keypoints[0].radius, 0.015);
}

TEST(GrippersHandPoints, BadEntryIsAnErrorNamingFileLineEntryAndKey) {
  const std::filesystem::path file = scratch_dir("bad") / "points.toml";
  std::ofstream(file) << "[[contact]]\nlink = \"tip\"\nposition = [0, 0, 0]\nnormal = [0, 1]\n";
  try {
    read_hand_points(file);
    FAIL() << "a normal with two components was accepted";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(file.string()), std::string::npos) << message;
    EXPECT_NE(message.find("line 1"), std::string::npos) << message;
    EXPECT_NE(message.find("contact[0]"), std::string::npos) << message;
    EXPECT_NE(message.find("'normal'"), std::string::npos) << message;
  }
  std::ofstream(file) << "[[contacts]]\nlink = \"tip\"\n";
  EXPECT_THROW(read_hand_points(file), std::runtime_error);
}

TEST(GrippersHandModel, PointsOnAnUnknownLinkAreAnError) {
  const LeapHandFiles files = shipped_leap_hand(HandSide::kRight);
  const std::filesystem::path points = scratch_dir("unknown_link") / "points.toml";
  std::ofstream(points)
      << "[[keypoint]]\nlink = \"pinky_distal\"\ncenter = [0, 0, 0]\nradius = 0.01\n";
  try {
    load_hand_model(files.urdf, points);
    FAIL() << "a point on a link the URDF lacks was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("pinky_distal"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(points.string()), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace grip::grippers
