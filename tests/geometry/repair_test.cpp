// Repair: what it fixes (duplicates, flipped faces, holes, self-intersection), what it reports,
// and the inputs it refuses (empty, flat).
#include "src/geometry/repair.hpp"

#include <gtest/gtest.h>

#include <string>

#include "src/geometry/mesh_measures.hpp"
#include "src/geometry/signed_distance.hpp"
#include "tests/geometry/test_meshes.hpp"

namespace grip::geometry {
namespace {

// The box with every triangle given its own three corners, as an STL file stores it.
SurfaceMesh unshared_corners(const SurfaceMesh& mesh) {
  SurfaceMesh soup;
  soup.vertices.resize(3 * mesh.triangles.rows(), 3);
  soup.triangles.resize(mesh.triangles.rows(), 3);
  for (Eigen::Index f = 0; f < mesh.triangles.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      soup.vertices.row(3 * f + k) = mesh.vertices.row(mesh.triangles(f, k));
      soup.triangles(f, k) = static_cast<int>(3 * f + k);
    }
  }
  return soup;
}

TEST(GeometryRepairTest, CleanClosedSurfaceIsUnchanged) {
  const SurfaceMesh box = testing::box(0.05, 0.1, 0.2);
  const RepairedSurface repaired = repair_surface(box);
  EXPECT_FALSE(repaired.report.alpha_wrapped);
  EXPECT_EQ(repaired.report.faces_reoriented, 0);
  EXPECT_EQ(repaired.report.points_removed, 0);
  EXPECT_EQ(repaired.mesh.triangles.rows(), 12);
  EXPECT_NEAR(repaired.report.volume, 0.1 * 0.2 * 0.4, 1e-15);
}

TEST(GeometryRepairTest, MergesDuplicatePointsAndReorientsInwardSurface) {
  SurfaceMesh soup = unshared_corners(testing::box(0.05, 0.05, 0.05));
  soup.triangles.col(1).swap(soup.triangles.col(2));  // every face inward
  const RepairedSurface repaired = repair_surface(soup);
  EXPECT_EQ(repaired.report.points_removed, 36 - 8);
  EXPECT_EQ(repaired.report.faces_reoriented, 12);
  EXPECT_FALSE(repaired.report.alpha_wrapped);
  EXPECT_EQ(repaired.mesh.vertices.rows(), 8);
  EXPECT_NEAR(repaired.report.volume, 0.001, 1e-15);
  EXPECT_NO_THROW(SignedDistance{repaired.mesh}) << "the result is closed";
}

TEST(GeometryRepairTest, FlipsOneWrongFace) {
  SurfaceMesh box = testing::box(0.05, 0.05, 0.05);
  std::swap(box.triangles(3, 1), box.triangles(3, 2));
  const RepairedSurface repaired = repair_surface(box);
  EXPECT_EQ(repaired.report.faces_reoriented, 1);
  EXPECT_NEAR(repaired.report.volume, 0.001, 1e-15);
}

TEST(GeometryRepairTest, RemovesDegenerateAndDuplicateFacesAndFillsAHole) {
  const SurfaceMesh box = testing::box(0.05, 0.05, 0.05);
  SurfaceMesh broken;
  broken.vertices = box.vertices;
  // Drop the two triangles of the top face (a square hole), duplicate one face and add one
  // whose corners repeat a point.
  broken.triangles.resize(12, 3);
  broken.triangles.topRows(2) = box.triangles.topRows(2);
  broken.triangles.middleRows(2, 8) = box.triangles.bottomRows(8);
  broken.triangles.row(10) = box.triangles.row(0);
  broken.triangles.row(11) << 0, 0, 1;
  const RepairedSurface repaired = repair_surface(broken);
  EXPECT_EQ(repaired.report.faces_removed, 2);
  EXPECT_EQ(repaired.report.holes_filled, 1);
  EXPECT_FALSE(repaired.report.alpha_wrapped);
  EXPECT_NEAR(repaired.report.volume, 0.001, 1e-15);
  EXPECT_NE(repaired.report.summary().find("filled 1 holes"), std::string::npos);
}

TEST(GeometryRepairTest, SelfIntersectingSurfaceIsAlphaWrappedToTheUnion) {
  // Two overlapping cubes as one soup: their union is a 0.1 x 0.1 x 0.15 box.
  const SurfaceMesh a = testing::box(0.05, 0.05, 0.05);
  SurfaceMesh both;
  both.vertices.resize(16, 3);
  both.vertices.topRows(8) = a.vertices;
  both.vertices.bottomRows(8) = a.vertices;
  both.vertices.bottomRows(8).col(2).array() += 0.05;
  both.triangles.resize(24, 3);
  both.triangles.topRows(12) = a.triangles;
  both.triangles.bottomRows(12) = a.triangles.array() + 8;
  RepairOptions options;
  options.alpha_ratio = 1.0 / 50.0;
  options.offset_ratio = 1.0 / 2000.0;
  const RepairedSurface repaired = repair_surface(both, options);
  EXPECT_TRUE(repaired.report.self_intersecting);
  EXPECT_TRUE(repaired.report.alpha_wrapped);
  // The wrap lies outside the input by about the offset: its volume exceeds the union's by
  // at most area x offset, and is no smaller.
  const double diagonal = bounding_box_diagonal(both.vertices);
  const double offset = options.offset_ratio * diagonal;
  const double exact = 0.1 * 0.1 * 0.15;
  const double area = 2 * 0.1 * 0.1 + 4 * 0.1 * 0.15;
  EXPECT_GT(repaired.report.volume, exact);
  EXPECT_LT(repaired.report.volume, exact + 1.5 * area * offset);
  EXPECT_NO_THROW(SignedDistance{repaired.mesh}) << "the result is closed";

  options.allow_alpha_wrap = false;
  EXPECT_THROW(repair_surface(both, options), std::invalid_argument);
}

TEST(GeometryRepairTest, EmptyMeshIsAnError) {
  try {
    repair_surface(SurfaceMesh{}, {}, "'empty.obj'");
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'empty.obj' is empty"), std::string::npos) << e.what();
  }
}

TEST(GeometryRepairTest, FlatMeshIsAZeroVolumeError) {
  SurfaceMesh flat = testing::box(0.05, 0.05, 0.05);
  flat.vertices.col(2).setZero();  // squashed into the plane z = 0
  try {
    repair_surface(flat, {}, "'flat.obj'");
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'flat.obj' has zero volume"), std::string::npos)
        << e.what();
  }
}

TEST(GeometryRepairTest, ScaleWarningCatchesMillimetres) {
  const SurfaceMesh metres = testing::box(0.05, 0.05, 0.05);
  EXPECT_TRUE(metric_scale_warning(metres.vertices, "a.obj").empty());
  const std::string warning = metric_scale_warning(metres.vertices * 1000.0, "a.obj");
  EXPECT_NE(warning.find("a.obj"), std::string::npos);
  EXPECT_NE(warning.find("scale it by 0.001"), std::string::npos);
  EXPECT_NE(metric_scale_warning(metres.vertices * 1e-3, "a.obj").find("1000"), std::string::npos);
}

}  // namespace
}  // namespace grip::geometry
