#include "src/grippers/kinematic_tree.hpp"

#include <gtest/gtest.h>
#include <unistd.h>
#include <urdf_parser/urdf_parser.h>

#include <cmath>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>

#include "src/geometry/mesh_io.hpp"
#include "src/geometry/mesh_measures.hpp"
#include "src/geometry/primitives.hpp"
#include "src/grippers/leap_hand.hpp"
#include "tests/grippers/mesh_checks.hpp"

namespace grip::grippers {
namespace {

// A fresh folder per test under the system temp folder.
std::filesystem::path scratch_dir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("grip_grippers_" + name + "_" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

void write_file(const std::filesystem::path& file, const std::string& text) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream(file) << text;
}

// Joint values drawn uniformly inside the limits, `margin` away from them.
Eigen::VectorXd random_configuration(const KinematicTree& tree, std::mt19937& rng,
                                     double margin = 0.0) {
  Eigen::VectorXd q(tree.dof_count());
  for (int d = 0; d < tree.dof_count(); ++d) {
    std::uniform_real_distribution<double> u(tree.lower_limits()[d] + margin,
                                             tree.upper_limits()[d] - margin);
    q[d] = u(rng);
  }
  return q;
}

Eigen::Isometry3d some_base_pose() {
  Eigen::Isometry3d base = Eigen::Isometry3d::Identity();
  base.rotate(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()));
  base.translation() = Eigen::Vector3d(0.3, -0.1, 0.8);
  return base;
}

class GrippersShippedRightHand : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    hand_ = new KinematicTree(KinematicTree::from_urdf(shipped_leap_hand(HandSide::kRight).urdf));
  }
  static void TearDownTestSuite() { delete hand_; }
  static KinematicTree* hand_;
};
KinematicTree* GrippersShippedRightHand::hand_ = nullptr;

TEST_F(GrippersShippedRightHand, HasSixteenJointsWithTheLeapHandLimits) {
  ASSERT_EQ(hand_->dof_count(), 16);
  const double finger[4][2] = {{-1.047, 1.047}, {-0.314, 2.23}, {-0.506, 1.885}, {-0.366, 2.042}};
  const double thumb[4][2] = {{-0.349, 2.094}, {-0.47, 2.443}, {-1.20, 1.90}, {-1.34, 1.88}};
  const char* names[4][4] = {{"index_abd", "index_mcp", "index_pip", "index_dip"},
                             {"middle_abd", "middle_mcp", "middle_pip", "middle_dip"},
                             {"ring_abd", "ring_mcp", "ring_pip", "ring_dip"},
                             {"thumb_rot", "thumb_abd", "thumb_mcp", "thumb_ip"}};
  for (int f = 0; f < 4; ++f) {
    for (int j = 0; j < 4; ++j) {
      const int d = 4 * f + j;
      EXPECT_EQ(hand_->dof_joint(d).name, names[f][j]);
      EXPECT_EQ(hand_->dof_index(names[f][j]), d);
      EXPECT_EQ(hand_->lower_limits()[d], f < 3 ? finger[j][0] : thumb[j][0]) << names[f][j];
      EXPECT_EQ(hand_->upper_limits()[d], f < 3 ? finger[j][1] : thumb[j][1]) << names[f][j];
    }
  }
}

TEST_F(GrippersShippedRightHand, PalmIsAboutTenCentimetresAndLinksAFewCentimetres) {
  const auto& palm = hand_->links()[static_cast<std::size_t>(hand_->link_index("palm"))].surface;
  EXPECT_NEAR(palm.vertices.col(0).maxCoeff() - palm.vertices.col(0).minCoeff(), 0.10, 1e-12);
  for (const KinematicLink& link : hand_->links()) {
    ASSERT_GT(link.surface.triangles.rows(), 0) << link.name;
    EXPECT_TRUE(testing::is_closed_and_oriented(link.surface)) << link.name;
    EXPECT_GT(geometry::surface_volume(link.surface), 0.0) << link.name;
    const double extent = geometry::bounding_box_diagonal(link.surface.vertices);
    EXPECT_GT(extent, 0.02) << link.name;
    EXPECT_LT(extent, 0.15) << link.name;
  }
}

// Forward kinematics recomputed from urdfdom's own numbers, composing origin * rotation about
// the axis with Eigen::AngleAxis from the link up to the root.
TEST_F(GrippersShippedRightHand, ForwardKinematicsMatchesComposingTheUrdfJointsByHand) {
  const auto model = urdf::parseURDFFile(shipped_leap_hand(HandSide::kRight).urdf.string());
  ASSERT_TRUE(model);
  std::mt19937 rng(7);
  const Eigen::Isometry3d base = some_base_pose();
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd q = random_configuration(*hand_, rng);
    const std::vector<Eigen::Isometry3d> poses = hand_->link_poses(base, q);
    for (const KinematicLink& link : hand_->links()) {
      Eigen::Matrix4d expected = Eigen::Matrix4d::Identity();
      for (auto l = model->getLink(link.name); l->parent_joint;
           l = model->getLink(l->parent_joint->parent_link_name)) {
        const urdf::Joint& joint = *l->parent_joint;
        const urdf::Pose& origin = joint.parent_to_joint_origin_transform;
        double roll, pitch, yaw;
        origin.rotation.getRPY(roll, pitch, yaw);
        Eigen::Matrix4d step = Eigen::Matrix4d::Identity();
        step.topLeftCorner<3, 3>() =
            (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
             Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
             Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()) *
             Eigen::AngleAxisd(q[hand_->dof_index(joint.name)],
                               Eigen::Vector3d(joint.axis.x, joint.axis.y, joint.axis.z)))
                .toRotationMatrix();
        step.topRightCorner<3, 1>() =
            Eigen::Vector3d(origin.position.x, origin.position.y, origin.position.z);
        expected = step * expected;
      }
      expected = base.matrix() * expected;
      EXPECT_LT((poses[static_cast<std::size_t>(hand_->link_index(link.name))].matrix() - expected)
                    .cwiseAbs()
                    .maxCoeff(),
                1e-13)
          << link.name;
    }
  }
}

TEST_F(GrippersShippedRightHand, JacobianMatchesCentralDifferencesOfForwardKinematics) {
  std::mt19937 rng(11);
  const Eigen::Isometry3d base = some_base_pose();
  const double h = 1e-6;
  for (const std::string link : {"index_distal", "thumb_distal", "ring_intermediate", "palm"}) {
    const int l = hand_->link_index(link);
    const Eigen::Vector3d point(0.02, -0.004, 0.009);
    const Eigen::VectorXd q = random_configuration(*hand_, rng, 2 * h);
    const auto jacobian = hand_->point_jacobian(hand_->link_poses(base, q), l, point);
    for (int d = 0; d < hand_->dof_count(); ++d) {
      Eigen::VectorXd plus = q, minus = q;
      plus[d] += h;
      minus[d] -= h;
      const Eigen::Isometry3d a = hand_->link_poses(base, plus)[static_cast<std::size_t>(l)];
      const Eigen::Isometry3d b = hand_->link_poses(base, minus)[static_cast<std::size_t>(l)];
      const Eigen::Vector3d velocity = (a * point - b * point) / (2 * h);
      const Eigen::AngleAxisd turn(a.linear() * b.linear().transpose());
      const Eigen::Vector3d angular = turn.angle() * turn.axis() / (2 * h);
      EXPECT_LT((jacobian.col(d).head<3>() - velocity).norm(), 1e-8) << link << " dof " << d;
      EXPECT_LT((jacobian.col(d).tail<3>() - angular).norm(), 1e-8) << link << " dof " << d;
    }
  }
}

TEST_F(GrippersShippedRightHand, JointLimitsAreEnforced) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(16);
  EXPECT_TRUE(hand_->within_limits(q));
  q[hand_->dof_index("index_pip")] = 1.886;
  EXPECT_FALSE(hand_->within_limits(q));
  try {
    hand_->link_poses(Eigen::Isometry3d::Identity(), q);
    FAIL() << "a joint value beyond its limit was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("index_pip"), std::string::npos) << e.what();
  }
  const Eigen::VectorXd clamped = hand_->clamp_to_limits(q);
  EXPECT_EQ(clamped[hand_->dof_index("index_pip")], 1.885);
  EXPECT_TRUE(hand_->within_limits(clamped));
  EXPECT_THROW(hand_->link_poses(Eigen::Isometry3d::Identity(), Eigen::VectorXd::Zero(15)),
               std::invalid_argument);
}

TEST_F(GrippersShippedRightHand, LeftHandIsTheMirrorImage) {
  const KinematicTree left = KinematicTree::from_urdf(shipped_leap_hand(HandSide::kLeft).urdf);
  ASSERT_EQ(left.dof_count(), 16);
  EXPECT_EQ(left.lower_limits(), hand_->lower_limits());
  EXPECT_EQ(left.upper_limits(), hand_->upper_limits());
  const Eigen::Vector3d m(1.0, -1.0, 1.0);
  std::mt19937 rng(3);
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd q = random_configuration(*hand_, rng);
    const auto right_poses = hand_->link_poses(Eigen::Isometry3d::Identity(), q);
    const auto left_poses = left.link_poses(Eigen::Isometry3d::Identity(), q);
    for (std::size_t i = 0; i < right_poses.size(); ++i) {
      ASSERT_EQ(left.links()[i].name, hand_->links()[i].name);
      const Eigen::Vector3d p(0.011, 0.007, -0.004);  // any point of the link frame
      EXPECT_LT((left_poses[i] * p.cwiseProduct(m) - (right_poses[i] * p).cwiseProduct(m)).norm(),
                1e-14)
          << hand_->links()[i].name;
    }
    // Whole surfaces: the left's vertices are the right's mirrored.
    const geometry::SurfaceMesh right_surface = hand_->posed_surface(right_poses);
    const geometry::SurfaceMesh left_surface = left.posed_surface(left_poses);
    ASSERT_EQ(left_surface.vertices.rows(), right_surface.vertices.rows());
    EXPECT_LT(
        (left_surface.vertices - right_surface.vertices * m.asDiagonal()).cwiseAbs().maxCoeff(),
        1e-14);
  }
}

TEST(GrippersUrdf, MissingUrdfIsAnErrorNamingTheFile) {
  const std::filesystem::path missing = scratch_dir("missing") / "no_such_hand.urdf";
  try {
    KinematicTree::from_urdf(missing);
    FAIL() << "a missing URDF loaded";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos) << e.what();
  }
}

TEST(GrippersUrdf, MalformedUrdfIsAnErrorNamingTheFile) {
  const std::filesystem::path file = scratch_dir("malformed") / "broken.urdf";
  write_file(file, "<robot name=\"x\"><link name=\"a\"></robot>");
  try {
    KinematicTree::from_urdf(file);
    FAIL() << "a malformed URDF loaded";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
  }
}

TEST(GrippersUrdf, MissingMeshIsAnErrorNamingTheUrdfTheLinkAndTheMesh) {
  const std::filesystem::path file = scratch_dir("missing_mesh") / "hand.urdf";
  write_file(file, R"(<robot name="h">
  <link name="base"><visual><geometry><mesh filename="meshes/gone.stl"/></geometry></visual></link>
</robot>)");
  try {
    KinematicTree::from_urdf(file);
    FAIL() << "a URDF with a missing mesh loaded";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(file.string()), std::string::npos) << message;
    EXPECT_NE(message.find("'base'"), std::string::npos) << message;
    EXPECT_NE(message.find("meshes/gone.stl"), std::string::npos) << message;
  }
}

// package:// names resolve inside the URDF's folder or a folder above it; primitives and mesh
// scales become closed outward surfaces; prismatic and continuous joints work.
TEST(GrippersUrdf, ResolvesPackageMeshesScalesPrimitivesAndJointTypes) {
  const std::filesystem::path root = scratch_dir("package");
  std::filesystem::create_directories(root / "my_hand" / "meshes");
  geometry::write_obj(root / "my_hand" / "meshes" / "cube.obj",
                      geometry::make_box(Eigen::Vector3d::Ones()));
  // An ASCII STL corner tetrahedron (volume 1/6), faces outward, as hand vendors ship them.
  write_file(root / "my_hand" / "meshes" / "corner.STL", R"(solid corner
facet normal 0 0 -1
 outer loop
  vertex 0 0 0
  vertex 0 1 0
  vertex 1 0 0
 endloop
endfacet
facet normal 0 -1 0
 outer loop
  vertex 0 0 0
  vertex 1 0 0
  vertex 0 0 1
 endloop
endfacet
facet normal -1 0 0
 outer loop
  vertex 0 0 0
  vertex 0 0 1
  vertex 0 1 0
 endloop
endfacet
facet normal 1 1 1
 outer loop
  vertex 1 0 0
  vertex 0 1 0
  vertex 0 0 1
 endloop
endfacet
endsolid corner
)");
  const std::filesystem::path file = root / "my_hand" / "urdf" / "hand.urdf";
  write_file(file, R"(<robot name="h">
  <link name="base">
    <visual><geometry><mesh filename="package://my_hand/meshes/cube.obj" scale="0.1 -0.2 0.3"/></geometry></visual>
    <visual><geometry><mesh filename="../meshes/corner.STL" scale="0.01 0.01 0.01"/></geometry></visual>
  </link>
  <link name="slider"><collision><geometry><box size="0.1 0.2 0.3"/></geometry></collision></link>
  <link name="wheel"><visual><origin xyz="0 0 0.1" rpy="0.3 0 0"/><geometry><cylinder radius="0.05" length="0.02"/></geometry></visual></link>
  <joint name="slide" type="prismatic">
    <parent link="base"/><child link="slider"/><origin xyz="0 0 0.5" rpy="0 0 0"/>
    <axis xyz="0 0 2"/><limit lower="-0.1" upper="0.2" effort="1" velocity="1"/>
  </joint>
  <joint name="spin" type="continuous">
    <parent link="slider"/><child link="wheel"/><origin xyz="0.1 0 0" rpy="0 0 0"/><axis xyz="1 0 0"/>
  </joint>
</robot>)");
  const KinematicTree tree = KinematicTree::from_urdf(file);
  ASSERT_EQ(tree.links().size(), 3u);
  EXPECT_NEAR(geometry::surface_volume(tree.links()[0].surface), 0.1 * 0.2 * 0.3 + 1e-6 / 6.0,
              1e-15);
  EXPECT_NEAR(geometry::surface_volume(tree.links()[1].surface), 0.1 * 0.2 * 0.3, 1e-15);
  EXPECT_GT(geometry::surface_volume(tree.links()[2].surface), 0.0);
  EXPECT_TRUE(std::isinf(tree.lower_limits()[tree.dof_index("spin")]));
  Eigen::VectorXd q(2);
  q << 0.15, 1.0;
  const auto poses = tree.link_poses(Eigen::Isometry3d::Identity(), q);
  EXPECT_LT((poses[1].translation() - Eigen::Vector3d(0.0, 0.0, 0.65)).norm(), 1e-15);
  const auto jacobian = tree.point_jacobian(poses, 2, Eigen::Vector3d::Zero());
  EXPECT_LT(
      (jacobian.col(0) - (Eigen::Matrix<double, 6, 1>() << 0, 0, 1, 0, 0, 0).finished()).norm(),
      1e-15);
  EXPECT_THROW(tree.dof_index("nonexistent"), std::out_of_range);
}

}  // namespace
}  // namespace grip::grippers
