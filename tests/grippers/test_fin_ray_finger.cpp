#include "src/grippers/fin_ray_finger.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "src/geometry/boundary_surface.hpp"
#include "src/geometry/mesh_measures.hpp"
#include "src/geometry/tet_quality.hpp"
#include "tests/grippers/mesh_checks.hpp"

namespace grip::grippers {
namespace {

// The bounds this finger promises at every resolution the tests use. Four layers across the
// 22 mm depth stretch the tets 1.5:1 along it: their smallest dihedral angle is 11.8 degrees.
constexpr double kMinDihedralBoundDeg = 11.0;
constexpr double kSliverBoundDeg = 10.0;

class GrippersDefaultFinRay : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { finger_ = new FinRayFinger(make_fin_ray_finger()); }
  static void TearDownTestSuite() { delete finger_; }
  static FinRayFinger* finger_;
};
FinRayFinger* GrippersDefaultFinRay::finger_ = nullptr;

TEST_F(GrippersDefaultFinRay, HasAbout1100VerticesAnd3100Tets) {
  EXPECT_GT(finger_->mesh.vertices.rows(), 1000);
  EXPECT_LT(finger_->mesh.vertices.rows(), 1250);
  EXPECT_GT(finger_->mesh.tets.rows(), 2800);
  EXPECT_LT(finger_->mesh.tets.rows(), 3400);
}

TEST_F(GrippersDefaultFinRay, HasNoInvertedOrSliverTets) {
  const geometry::TetQuality q = geometry::tet_quality(finger_->mesh, kSliverBoundDeg);
  EXPECT_EQ(q.inverted_count, 0);
  EXPECT_GT(q.min_volume, 0.0);
  EXPECT_EQ(q.sliver_count, 0);
  EXPECT_GT(q.min_dihedral_deg, kMinDihedralBoundDeg);
  EXPECT_LT(q.max_dihedral_deg, 180.0 - kMinDihedralBoundDeg);
}

TEST_F(GrippersDefaultFinRay, VolumeIsProfileAreaTimesDepth) {
  // The profile mesh covers exactly the walls, ribs and plate (not the cavities).
  const FinRayOptions o;
  const double volume = geometry::tet_quality(finger_->mesh).total_volume;
  EXPECT_NEAR(volume, finger_->profile_area * o.depth, 1e-12 * volume);
  // Material is less than the full tapered outline and more than the two walls alone.
  const double outline = 0.5 * (o.base_width + o.tip_width) * o.length;
  EXPECT_LT(finger_->profile_area, outline - 0.5 * outline);
  EXPECT_GT(finger_->profile_area, 2.0 * o.wall_thickness * o.length);
}

TEST_F(GrippersDefaultFinRay, BoundaryIsClosedWithOneHandlePerCavity) {
  const geometry::SurfaceMesh surface = geometry::boundary_surface(finger_->mesh);
  EXPECT_TRUE(testing::is_closed_and_oriented(surface));
  // Each cavity runs through the whole depth: genus = rib_count + 1, chi = 2 - 2 genus.
  const FinRayOptions o;
  EXPECT_EQ(testing::euler_characteristic(surface), 2 - 2 * (o.rib_count + 1));
  EXPECT_NEAR(geometry::surface_volume(surface), geometry::tet_quality(finger_->mesh).total_volume,
              1e-12);
}

TEST_F(GrippersDefaultFinRay, ContactFaceIsThePlaneYZeroAndTheFingerFitsItsFrame) {
  const FinRayOptions o;
  const auto& v = finger_->mesh.vertices;
  EXPECT_DOUBLE_EQ(v.col(1).minCoeff(), 0.0);
  EXPECT_DOUBLE_EQ(v.col(1).maxCoeff(), o.base_width);
  EXPECT_DOUBLE_EQ(v.col(2).minCoeff(), 0.0);
  EXPECT_DOUBLE_EQ(v.col(2).maxCoeff(), o.length);
  EXPECT_DOUBLE_EQ(v.col(0).minCoeff(), -0.5 * o.depth);
  EXPECT_DOUBLE_EQ(v.col(0).maxCoeff(), 0.5 * o.depth);
  // The contact face spans the whole length.
  double lowest = 1.0, highest = 0.0;
  for (Eigen::Index i = 0; i < v.rows(); ++i) {
    if (v(i, 1) == 0.0) {
      lowest = std::min(lowest, v(i, 2));
      highest = std::max(highest, v(i, 2));
    }
  }
  EXPECT_EQ(lowest, 0.0);
  EXPECT_EQ(highest, o.length);
}

TEST_F(GrippersDefaultFinRay, MountRegionIsExactlyTheBasePlate) {
  const FinRayOptions o;
  const auto& v = finger_->mesh.vertices;
  std::vector<int> expected;
  for (Eigen::Index i = 0; i < v.rows(); ++i) {
    if (v(i, 2) <= o.base_thickness * (1.0 + 1e-9)) expected.push_back(static_cast<int>(i));
  }
  EXPECT_EQ(finger_->mount_vertices, expected);
  // It holds the whole mount face and leaves the rest of the finger free.
  int on_face = 0;
  for (int i : finger_->mount_vertices) on_face += v(i, 2) == 0.0;
  EXPECT_GE(on_face, 2 * (o.layers + 1));
  EXPECT_LT(finger_->mount_vertices.size(), static_cast<std::size_t>(v.rows()) / 3);
}

TEST_F(GrippersDefaultFinRay, MaterialIsGripsTpu) {
  EXPECT_EQ(finger_->material.youngs_modulus, 9.4e6);
  EXPECT_EQ(finger_->material.friction, 3.5);
  EXPECT_GT(finger_->material.density, 1000.0);
  EXPECT_LT(finger_->material.density, 1300.0);
}

TEST(GrippersFinRay, IsDeterministic) {
  const FinRayFinger a = make_fin_ray_finger();
  const FinRayFinger b = make_fin_ray_finger();
  EXPECT_EQ(a.mesh.vertices, b.mesh.vertices);
  EXPECT_EQ(a.mesh.tets, b.mesh.tets);
}

TEST(GrippersFinRay, FinerResolutionKeepsTheQualityBound) {
  FinRayOptions o;
  o.edge_length = 0.0025;
  o.layers = 11;
  const FinRayFinger finger = make_fin_ray_finger(o);
  const geometry::TetQuality q = geometry::tet_quality(finger.mesh, kSliverBoundDeg);
  EXPECT_GT(finger.mesh.tets.rows(), 9000);
  EXPECT_EQ(q.inverted_count, 0);
  EXPECT_EQ(q.sliver_count, 0);
  EXPECT_GT(q.min_dihedral_deg, kMinDihedralBoundDeg);
  EXPECT_NEAR(q.total_volume, finger.profile_area * o.depth, 1e-12 * q.total_volume);
}

TEST(GrippersFinRay, RejectsImpossibleProfiles) {
  FinRayOptions wide_tip;
  wide_tip.tip_width = 0.04;
  EXPECT_THROW(make_fin_ray_finger(wide_tip), std::invalid_argument);
  FinRayOptions thick_walls;
  thick_walls.wall_thickness = 0.014;
  EXPECT_THROW(make_fin_ray_finger(thick_walls), std::invalid_argument);
  FinRayOptions crowded;
  crowded.rib_count = 40;
  EXPECT_THROW(make_fin_ray_finger(crowded), std::invalid_argument);
  FinRayOptions no_layers;
  no_layers.layers = 0;
  EXPECT_THROW(make_fin_ray_finger(no_layers), std::invalid_argument);
}

}  // namespace
}  // namespace grip::grippers
