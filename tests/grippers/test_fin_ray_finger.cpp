#include "src/grippers/fin_ray_finger.hpp"

#include <gtest/gtest.h>

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "src/geometry/boundary_surface.hpp"
#include "src/geometry/mesh_measures.hpp"
#include "src/geometry/tet_quality.hpp"
#include "tests/grippers/mesh_checks.hpp"

namespace grip::grippers {
namespace {

// The bounds the fingers promise at every resolution the tests use. The production finger's
// smallest dihedral angle is 16.4 degrees; four layers across the 80 mm finger's 22 mm width
// stretch its tets 1.5:1 along it: 11.8.
constexpr double kMinDihedralBoundDeg = 11.0;
constexpr double kSliverBoundDeg = 10.0;

// Each test runs on the production finger (solid, GRIP's size) and on the 80 mm variant
// (hollow, five ribs).
struct Shape {
  const char* name;
  FinRayOptions options;
};

class GrippersFinRayShapes : public ::testing::TestWithParam<Shape> {
 protected:
  const FinRayOptions& o() const { return GetParam().options; }
  // Each shape's finger, meshed once for all its tests.
  const FinRayFinger& finger() const {
    static std::map<std::string, FinRayFinger> meshed;
    auto it = meshed.find(GetParam().name);
    if (it == meshed.end()) it = meshed.emplace(GetParam().name, make_fin_ray_finger(o())).first;
    return it->second;
  }
};

INSTANTIATE_TEST_SUITE_P(Fingers, GrippersFinRayShapes,
                         ::testing::Values(Shape{"production", FinRayOptions{}},
                                           Shape{"eighty_mm", fin_ray_80mm_options()}),
                         [](const auto& info) { return std::string(info.param.name); });

// GRIP's finger (its released models' UMI finger body): 123.5 mm from the mount to the tip,
// 41.5 mm deep at the mount, 26 mm wide; meshed about as finely as GRIP's finest (1,486
// vertices, 6,506 tets).
TEST(GrippersFinRay, TheProductionFingerHasGripsSizeAndAbout4500Tets) {
  const FinRayFinger finger = make_fin_ray_finger();
  const auto& v = finger.mesh.vertices;
  EXPECT_NEAR(v.col(2).maxCoeff() - v.col(2).minCoeff(), 0.1235, 1e-12);
  EXPECT_NEAR(v.col(1).maxCoeff() - v.col(1).minCoeff(), 0.0415, 1e-12);
  EXPECT_NEAR(v.col(0).maxCoeff() - v.col(0).minCoeff(), 0.026, 1e-12);
  EXPECT_GT(finger.mesh.vertices.rows(), 1000);
  EXPECT_LT(finger.mesh.vertices.rows(), 1300);
  EXPECT_GT(finger.mesh.tets.rows(), 4000);
  EXPECT_LT(finger.mesh.tets.rows(), 5000);
}

// grip's first finger, kept as a variant: the mesh it always had.
TEST(GrippersFinRay, The80mmVariantIsTheFirstFinger) {
  const FinRayFinger finger = make_fin_ray_finger(fin_ray_80mm_options());
  EXPECT_EQ(finger.mesh.vertices.rows(), 1130);
  EXPECT_EQ(finger.mesh.tets.rows(), 3096);
  const auto& v = finger.mesh.vertices;
  EXPECT_DOUBLE_EQ(v.col(2).maxCoeff(), 0.080);
  EXPECT_DOUBLE_EQ(v.col(1).maxCoeff(), 0.030);
  EXPECT_DOUBLE_EQ(v.col(0).maxCoeff() - v.col(0).minCoeff(), 0.022);
}

TEST_P(GrippersFinRayShapes, HasNoInvertedOrSliverTets) {
  const geometry::TetQuality q = geometry::tet_quality(finger().mesh, kSliverBoundDeg);
  EXPECT_EQ(q.inverted_count, 0);
  EXPECT_GT(q.min_volume, 0.0);
  EXPECT_EQ(q.sliver_count, 0);
  EXPECT_GT(q.min_dihedral_deg, kMinDihedralBoundDeg);
  EXPECT_LT(q.max_dihedral_deg, 180.0 - kMinDihedralBoundDeg);
}

TEST_P(GrippersFinRayShapes, VolumeIsProfileAreaTimesDepth) {
  // The profile mesh covers exactly the material: the whole tapered outline when solid; the
  // walls, ribs and plate (not the cavities) when hollow.
  const double volume = geometry::tet_quality(finger().mesh).total_volume;
  EXPECT_NEAR(volume, finger().profile_area * o().depth, 1e-12 * volume);
  const double outline = 0.5 * (o().base_width + o().tip_width) * o().length;
  if (!o().hollow) {
    EXPECT_NEAR(finger().profile_area, outline, 1e-12 * outline);
    return;
  }
  // Material is less than half the outline and more than the two walls alone.
  EXPECT_LT(finger().profile_area, 0.5 * outline);
  EXPECT_GT(finger().profile_area, 2.0 * o().wall_thickness * o().length);
}

TEST_P(GrippersFinRayShapes, BoundaryIsClosedWithOneHandlePerCavity) {
  const geometry::SurfaceMesh surface = geometry::boundary_surface(finger().mesh);
  EXPECT_TRUE(testing::is_closed_and_oriented(surface));
  // Each cavity runs through the whole depth: genus = rib_count + 1, chi = 2 - 2 genus; a solid
  // finger is a sphere's shape.
  const int genus = o().hollow ? o().rib_count + 1 : 0;
  EXPECT_EQ(testing::euler_characteristic(surface), 2 - 2 * genus);
  EXPECT_NEAR(geometry::surface_volume(surface), geometry::tet_quality(finger().mesh).total_volume,
              1e-12);
}

TEST_P(GrippersFinRayShapes, ContactFaceIsThePlaneYZeroAndTheFingerFitsItsFrame) {
  const auto& v = finger().mesh.vertices;
  EXPECT_DOUBLE_EQ(v.col(1).minCoeff(), 0.0);
  EXPECT_DOUBLE_EQ(v.col(1).maxCoeff(), o().base_width);
  EXPECT_DOUBLE_EQ(v.col(2).minCoeff(), 0.0);
  EXPECT_DOUBLE_EQ(v.col(2).maxCoeff(), o().length);
  EXPECT_DOUBLE_EQ(v.col(0).minCoeff(), -0.5 * o().depth);
  EXPECT_DOUBLE_EQ(v.col(0).maxCoeff(), 0.5 * o().depth);
  // The contact face spans the whole length.
  double lowest = 1.0, highest = 0.0;
  for (Eigen::Index i = 0; i < v.rows(); ++i) {
    if (v(i, 1) == 0.0) {
      lowest = std::min(lowest, v(i, 2));
      highest = std::max(highest, v(i, 2));
    }
  }
  EXPECT_EQ(lowest, 0.0);
  EXPECT_EQ(highest, o().length);
}

TEST_P(GrippersFinRayShapes, MountRegionIsTheBottomBaseThickness) {
  const auto& v = finger().mesh.vertices;
  std::vector<int> expected;
  for (Eigen::Index i = 0; i < v.rows(); ++i) {
    if (v(i, 2) <= o().base_thickness * (1.0 + 1e-9)) expected.push_back(static_cast<int>(i));
  }
  EXPECT_EQ(finger().mount_vertices, expected);
  // It holds the whole mount face and leaves the rest of the finger free.
  int on_face = 0;
  for (int i : finger().mount_vertices) on_face += v(i, 2) == 0.0;
  EXPECT_GE(on_face, 2 * (o().layers + 1));
  EXPECT_LT(finger().mount_vertices.size(), static_cast<std::size_t>(v.rows()) / 3);
}

TEST_P(GrippersFinRayShapes, MaterialIsGripsTpu) {
  EXPECT_EQ(finger().material.youngs_modulus, 9.4e6);
  EXPECT_EQ(finger().material.friction, 3.5);
  EXPECT_GT(finger().material.density, 1000.0);
  EXPECT_LT(finger().material.density, 1300.0);
}

TEST(GrippersFinRay, IsDeterministic) {
  const FinRayFinger a = make_fin_ray_finger();
  const FinRayFinger b = make_fin_ray_finger();
  EXPECT_EQ(a.mesh.vertices, b.mesh.vertices);
  EXPECT_EQ(a.mesh.tets, b.mesh.tets);
}

TEST(GrippersFinRay, FinerResolutionKeepsTheQualityBound) {
  FinRayOptions o = fin_ray_80mm_options();
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
  wide_tip.tip_width = 0.042;
  EXPECT_THROW(make_fin_ray_finger(wide_tip), std::invalid_argument);
  // Walls and ribs measure only a hollow finger.
  FinRayOptions thick_walls = fin_ray_80mm_options();
  thick_walls.wall_thickness = 0.014;
  EXPECT_THROW(make_fin_ray_finger(thick_walls), std::invalid_argument);
  thick_walls.hollow = false;
  EXPECT_NO_THROW(make_fin_ray_finger(thick_walls));
  FinRayOptions crowded = fin_ray_80mm_options();
  crowded.rib_count = 40;
  EXPECT_THROW(make_fin_ray_finger(crowded), std::invalid_argument);
  FinRayOptions no_layers;
  no_layers.layers = 0;
  EXPECT_THROW(make_fin_ray_finger(no_layers), std::invalid_argument);
}

}  // namespace
}  // namespace grip::grippers
