// Tests of gripper descriptions: a finger meshed in millimetres along other axes enters grip's
// finger frame, the mount is a plane or a box, the gripper resolves as a described type, and
// every class of bad finger mesh or key gets one message naming the file, the key and the fix.
#include "src/grippers/gripper_description.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

#include "src/config/config.hpp"
#include "src/geometry/tet_quality.hpp"
#include "src/grippers/gripper_registry.hpp"
#include "tests/grippers/described_gripper_files.hpp"

namespace grip::grippers {
namespace {

namespace fs = std::filesystem;

class GripperDescription : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("grip_gripper_description_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // The message loading the description `text` (beside the box finger, or `mesh`) gives.
  std::string error(const std::string& text, const geometry::TetMesh& mesh) {
    testing::write_vtk_tets(dir_ / "finger.vtk", mesh);
    std::ofstream(dir_ / "gripper.toml") << text;
    try {
      load_gripper_description(dir_ / "gripper.toml");
    } catch (const config::ConfigError& e) {
      return e.what();
    }
    return "";
  }
  std::string error(const std::string& text) { return error(text, testing::box_finger_mm()); }

  fs::path dir_;
};

TEST_F(GripperDescription, AFingerInMillimetresAlongOtherAxesEntersTheFingerFrame) {
  const ParallelGripper gripper = load_gripper_description(testing::write_described_gripper(dir_));
  EXPECT_EQ(gripper.name, "test-soft-jaws");
  EXPECT_EQ(gripper.min_opening, 0.0);
  EXPECT_EQ(gripper.max_opening, 0.08);
  EXPECT_EQ(gripper.min_grasp_depth, 0.02);
  ASSERT_TRUE(gripper.soft_finger.has_value());
  const FinRayFinger& finger = *gripper.soft_finger;
  EXPECT_EQ(finger.mesh.tets.rows(), 480);
  EXPECT_EQ(finger.material.youngs_modulus, 2e6);
  EXPECT_EQ(finger.material.poisson_ratio, 0.4);
  EXPECT_EQ(finger.material.density, 1100.0);
  EXPECT_EQ(finger.material.friction, 1.0);
  EXPECT_EQ(finger.material.damping, FinRayMaterial{}.damping);

  // The file's x (10 mm, closing +x) is the finger's -y, its y (50 mm, tip +y) the finger's z,
  // its z (20 mm) the finger's x: the contact face on y = 0, the mount on z = 0.
  const Eigen::Vector3d lower = finger.mesh.vertices.colwise().minCoeff();
  const Eigen::Vector3d upper = finger.mesh.vertices.colwise().maxCoeff();
  EXPECT_TRUE(lower.isApprox(Eigen::Vector3d(-0.010, 0.0, 0.0), 1e-12)) << lower.transpose();
  EXPECT_TRUE(upper.isApprox(Eigen::Vector3d(0.010, 0.010, 0.050), 1e-12)) << upper.transpose();
  // The leading face (the file's x = +5 mm) is the contact face, y = 0.
  const geometry::TetMesh file = testing::box_finger_mm();
  for (Eigen::Index v = 0; v < file.vertices.rows(); ++v) {
    EXPECT_NEAR(finger.mesh.vertices(v, 1), 0.001 * (5.0 - file.vertices(v, 0)), 1e-15);
    EXPECT_NEAR(finger.mesh.vertices(v, 2), 0.001 * (file.vertices(v, 1) + 25.0), 1e-15);
  }
  const geometry::TetQuality quality = geometry::tet_quality(finger.mesh);
  EXPECT_EQ(quality.inverted_count, 0);
  EXPECT_NEAR(quality.total_volume, 0.010 * 0.020 * 0.050, 1e-15);

  // depth = 1 mm pins the mount face's 3 x 5 vertices, in increasing order.
  ASSERT_EQ(finger.mount_vertices.size(), 15u);
  for (const int v : finger.mount_vertices) EXPECT_EQ(finger.mesh.vertices(v, 2), 0.0);
  EXPECT_TRUE(std::is_sorted(finger.mount_vertices.begin(), finger.mount_vertices.end()));
  // The surface: the 3 x 11 x 5 grid's vertices but its 1 x 9 x 3 interior ones.
  EXPECT_EQ(gripper.finger_surface.vertices.rows(), 165 - 27);
}

// The shipped example describes grip's 80 mm fin-ray finger, exported by grip asset gallery
// (--finger 80mm): read back, it is the built-in gripper at those options bit for bit.
TEST(ShippedGripperDescription, TheExportedFinRayIsTheBuiltInOne) {
  const ParallelGripper described =
      load_gripper_description(std::filesystem::path(GRIP_JOBS_DIR) / "grippers/fin-ray-80mm.toml");
  const ParallelGripper built_in = make_umi_soft_gripper(fin_ray_80mm_options());
  EXPECT_EQ(described.name, "fin-ray-80mm");
  EXPECT_EQ(described.min_opening, built_in.min_opening);
  EXPECT_EQ(described.max_opening, built_in.max_opening);
  EXPECT_DOUBLE_EQ(described.min_grasp_depth, built_in.min_grasp_depth);
  ASSERT_TRUE(described.soft_finger.has_value());
  const FinRayFinger& a = *described.soft_finger;
  const FinRayFinger& b = *built_in.soft_finger;
  EXPECT_EQ(a.mesh.vertices, b.mesh.vertices);
  EXPECT_EQ(a.mesh.tets, b.mesh.tets);
  EXPECT_EQ(a.mount_vertices, b.mount_vertices);
  EXPECT_EQ(a.material.youngs_modulus, b.material.youngs_modulus);
  EXPECT_EQ(a.material.poisson_ratio, b.material.poisson_ratio);
  EXPECT_EQ(a.material.density, b.material.density);
  EXPECT_EQ(a.material.friction, b.material.friction);
  EXPECT_EQ(a.material.damping, b.material.damping);
  EXPECT_EQ(described.finger_surface.vertices, built_in.finger_surface.vertices);
  EXPECT_EQ(described.finger_surface.triangles, built_in.finger_surface.triangles);
}

TEST_F(GripperDescription, TheMountIsAPlaneOrABoxOfTheFilesCoordinates) {
  // The box around the file's y = -25 and -20 mm layers pins what depth = 5 mm pins.
  testing::write_vtk_tets(dir_ / "finger.vtk", testing::box_finger_mm());
  std::ofstream(dir_ / "plane.toml")
      << testing::described_gripper_text("finger.vtk", "depth = 0.005");
  std::ofstream(dir_ / "box.toml") << testing::described_gripper_text(
      "finger.vtk", "lower = [-6, -26, -11]\nupper = [6, -19, 11]");
  const ParallelGripper plane = load_gripper_description(dir_ / "plane.toml");
  const ParallelGripper box = load_gripper_description(dir_ / "box.toml");
  EXPECT_EQ(plane.soft_finger->mount_vertices.size(), 30u);
  EXPECT_EQ(plane.soft_finger->mount_vertices, box.soft_finger->mount_vertices);
}

// A finger that is not symmetric across its width (the box with one corner cell cut away): the
// second finger is the first turned half a turn, or with second_finger = "mirrored" its mirror
// image across the gripper's closing plane, positively oriented.
TEST_F(GripperDescription, TheSecondFingerIsTheFirstTurnedOrMirrored) {
  geometry::TetMesh notched = testing::box_finger_mm();
  // The last cell's six tets: the corner at the tip, +x and +z of the file.
  notched.tets.conservativeResize(notched.tets.rows() - 6, 4);
  testing::write_vtk_tets(dir_ / "finger.vtk", notched);
  std::string text = testing::described_gripper_text();
  std::ofstream(dir_ / "same.toml") << text;
  text.insert(text.find("\n[finger]"), "second_finger = \"mirrored\"\n");
  std::ofstream(dir_ / "mirrored.toml") << text;
  const ParallelGripper same = load_gripper_description(dir_ / "same.toml");
  const ParallelGripper mirrored = load_gripper_description(dir_ / "mirrored.toml");
  EXPECT_EQ(same.second_finger, SecondFinger::kSame);
  ASSERT_EQ(mirrored.second_finger, SecondFinger::kMirrored);

  const double opening = 0.03;
  const geometry::SurfaceMesh turned = same.surface(opening);
  const geometry::SurfaceMesh reflected = mirrored.surface(opening);
  const Eigen::Index n = same.finger_surface.vertices.rows();
  ASSERT_EQ(turned.vertices.rows(), 2 * n);
  for (Eigen::Index v = 0; v < n; ++v) {
    const Eigen::Vector3d p = turned.vertices.row(v);
    EXPECT_TRUE(Eigen::Vector3d(reflected.vertices.row(v)).isApprox(p, 1e-15));
    const Eigen::Vector3d half_turn(-p.x(), -p.y(), p.z());
    const Eigen::Vector3d mirror(p.x(), -p.y(), p.z());
    EXPECT_LT((Eigen::Vector3d(turned.vertices.row(n + v)) - half_turn).norm(), 1e-15);
    EXPECT_LT((Eigen::Vector3d(reflected.vertices.row(n + v)) - mirror).norm(), 1e-15);
  }
  // The notch: some corner of the mirror image is no corner of the turned finger.
  double apart = 0.0;
  for (Eigen::Index v = n; v < 2 * n; ++v) {
    double nearest = 1e300;
    for (Eigen::Index w = n; w < 2 * n; ++w) {
      nearest = std::min(nearest, (reflected.vertices.row(v) - turned.vertices.row(w)).norm());
    }
    apart = std::max(apart, nearest);
  }
  EXPECT_GT(apart, 0.004);
  // The mirrored finger's tets keep their orientation and its mount its vertices.
  const std::optional<FinRayFinger> second = mirrored.soft_finger_of(Jaw::kNegative);
  ASSERT_TRUE(second.has_value());
  EXPECT_EQ(geometry::tet_quality(second->mesh).inverted_count, 0);
  EXPECT_EQ(second->mount_vertices, mirrored.soft_finger->mount_vertices);
  EXPECT_EQ(mirrored.finger_surface_of(Jaw::kPositive).vertices, mirrored.finger_surface.vertices);
}

TEST_F(GripperDescription, ResolvesAsADescribedGripperType) {
  const fs::path file = testing::write_described_gripper(dir_);
  const GripperType type = resolve_gripper(file.string());
  EXPECT_EQ(type.kind, GripperKind::kDescribed);
  EXPECT_EQ(type.name, "test-soft-jaws");
  EXPECT_EQ(type.joints, 1);
  EXPECT_FALSE(type.is_hand());
  EXPECT_FALSE(type.meshed_finger);  // grip trial --finger-layers is the fin-ray's
  EXPECT_EQ(type.description, file);
  const ParallelGripper built = type.make_parallel(FinRayOptions{});
  EXPECT_EQ(built.soft_finger->mesh.tets.rows(), 480);
  // 480 tets against the fin-ray's thousands: a smaller share of the fin-ray's trial cost.
  EXPECT_GT(type.trial_cpu_seconds, 0.0);
  EXPECT_LT(type.trial_cpu_seconds, gripper_type(GripperKind::kFinRay).trial_cpu_seconds);

  EXPECT_EQ(resolve_gripper("fin-ray").kind, GripperKind::kFinRay);
  try {
    resolve_gripper("robotiq");
    FAIL() << "no error for an unknown gripper";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("or a gripper description file"), std::string::npos)
        << e.what();
  }
}

// Each class of finger mesh grip cannot simulate: the description's file and line, the key
// (finger.mesh), the mesh file and the fix.
TEST_F(GripperDescription, BadMeshesGetOneMessageNamingTheFileAndTheFix) {
  const std::string text = testing::described_gripper_text();
  const auto expect = [&](const std::string& message, const std::string& what) {
    EXPECT_NE(message.find("gripper.toml:"), std::string::npos) << message;
    EXPECT_NE(message.find(what), std::string::npos) << message;
  };

  geometry::TetMesh inverted = testing::box_finger_mm();
  std::swap(inverted.tets(7, 1), inverted.tets(7, 2));
  const std::string inverted_message = error(text, inverted);
  expect(inverted_message, "key 'finger.mesh'");
  expect(inverted_message, "finger.vtk");
  expect(inverted_message, "1 of 480 tets are inverted");

  // A tet of four nearly coplanar vertices, beside the finger.
  geometry::TetMesh degenerate = testing::box_finger_mm();
  const Eigen::Index n = degenerate.vertices.rows();
  degenerate.vertices.conservativeResize(n + 4, 3);
  degenerate.vertices.bottomRows(4) << 20, 0, 0, 21, 0, 0, 20, 1, 0, 21, 1, 1e-9;
  degenerate.tets.conservativeResize(degenerate.tets.rows() + 1, 4);
  degenerate.tets.bottomRows(1) << n, n + 1, n + 2, n + 3;
  expect(error(text, degenerate), "is degenerate");

  // A tet that touches the finger at one corner only: the boundary pinches there.
  geometry::TetMesh pinched = testing::box_finger_mm();
  pinched.vertices.conservativeResize(n + 3, 3);
  pinched.vertices.bottomRows(3) << 6, 26, 10, 5, 27, 10, 5, 26, 11;
  pinched.tets.conservativeResize(pinched.tets.rows() + 1, 4);
  const Eigen::Index corner = n - 1;  // (5, 25, 10), the file's last vertex
  ASSERT_TRUE(Eigen::Vector3d(pinched.vertices.row(corner)).isApprox(Eigen::Vector3d(5, 25, 10)));
  pinched.tets.bottomRows(1) << corner, n, n + 1, n + 2;
  const Eigen::Vector3d a = pinched.vertices.row(corner);
  const double volume = (Eigen::Vector3d(pinched.vertices.row(n)) - a)
                            .cross(Eigen::Vector3d(pinched.vertices.row(n + 1)) - a)
                            .dot(Eigen::Vector3d(pinched.vertices.row(n + 2)) - a);
  if (volume < 0) pinched.tets.bottomRows(1) << corner, n + 1, n, n + 2;
  expect(error(text, pinched), "not a closed manifold");

  // Millimetres read as metres: a finger 54 m across.
  expect(error(testing::described_gripper_text("finger.vtk", "depth = 0.001", "1.0")),
         "are its units millimetres? Scale it to metres");

  // A file that is no tet mesh, or none at all.
  expect(error(testing::described_gripper_text("finger.stl")), "not a tet mesh");
  fs::remove(dir_ / "finger.vtk");
  std::ofstream(dir_ / "gripper.toml") << testing::described_gripper_text("missing.vtk");
  try {
    load_gripper_description(dir_ / "gripper.toml");
    ADD_FAILURE() << "no error for a missing finger mesh";
  } catch (const config::ConfigError& e) {
    expect(e.what(), "missing.vtk");
  }
}

TEST_F(GripperDescription, AMountThatHoldsNothingIsRefused) {
  // A box beyond the finger selects no vertex.
  const std::string none =
      error(testing::described_gripper_text("finger.vtk",
                                            "lower = [50, 50, 50]\nupper = [60, 60, "
                                            "60]"));
  EXPECT_NE(none.find("key 'finger.mount.lower' selects no vertex"), std::string::npos) << none;
  // A box around one edge of the mount face: vertices on one line.
  const std::string line =
      error(testing::described_gripper_text("finger.vtk",
                                            "lower = [4, -26, -11]\nupper = [6, "
                                            "-24, 11]"));
  EXPECT_NE(line.find("pins 5 vertices on one line or point"), std::string::npos) << line;
  const std::string all = error(testing::described_gripper_text("finger.vtk", "depth = 1e308"));
  EXPECT_NE(all.find("pins every vertex of the finger"), std::string::npos) << all;
  const std::string both = error(testing::described_gripper_text(
      "finger.vtk", "depth = 0.001\nlower = [4, -26, -11]\nupper = [6, -24, 11]"));
  EXPECT_NE(both.find("either a depth (the plane) or a box"), std::string::npos) << both;
}

TEST_F(GripperDescription, KeysOutOfRangeNameTheKey) {
  std::string text = testing::described_gripper_text();
  const auto replaced = [&](const std::string& from, const std::string& to) {
    std::string t = text;
    t.replace(t.find(from), from.size(), to);
    return t;
  };
  EXPECT_NE(error(replaced("tip_axis = [0, 1, 0]", "tip_axis = [1, 1, 0]"))
                .find("key 'finger.tip_axis' must be perpendicular to closing_axis"),
            std::string::npos);
  EXPECT_NE(error(replaced("\"test-soft-jaws\"", "\"fin-ray\"")).find("a built-in gripper's"),
            std::string::npos);
  EXPECT_NE(error(replaced("[0.0, 0.08]", "[0, 80]")).find("is it in millimetres?"),
            std::string::npos);
  EXPECT_NE(error(replaced("grasp_depth = 0.02", "grasp_depth = 0.06"))
                .find("key 'gripper.grasp_depth' must lie in"),
            std::string::npos);
  EXPECT_NE(error(replaced("friction = 1.0", "fricton = 1.0")).find("did you mean"),
            std::string::npos);
  // A direction as long as doubles allow is still a direction.
  EXPECT_EQ(error(replaced("closing_axis = [1, 0, 0]", "closing_axis = [1e308, 0, 1e-300]")), "");
  EXPECT_NE(error(replaced("closing_axis = [1, 0, 0]", "closing_axis = [0, 0, 0]"))
                .find("key 'finger.closing_axis' must be a direction"),
            std::string::npos);
  EXPECT_NE(error(replaced("scale = 0.001", "scale = 1e-300"))
                .find("key 'finger.scale' makes the finger"),
            std::string::npos);
  EXPECT_NE(error(replaced("poisson_ratio = 0.4", "poisson_ratio = 0.5")).find("(-1, 0.5)"),
            std::string::npos);
}

}  // namespace
}  // namespace grip::grippers
