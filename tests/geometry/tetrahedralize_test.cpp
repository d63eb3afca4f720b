// Mesh_3 tetrahedralization: valid orientation, quality bound, volume, determinism, and the
// inputs it refuses.
#include "src/geometry/tetrahedralize.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "src/geometry/mesh_measures.hpp"
#include "tests/geometry/test_meshes.hpp"

namespace grip::geometry {
namespace {

// Exudation alone (perturbation is time-capped, so tests switch it off to stay
// machine-independent) keeps every dihedral angle above this in our measurements.
constexpr double kMinDihedralDeg = 3.0;

TetOptions exude_only(double edge_length) {
  TetOptions options;
  options.edge_length = edge_length;
  options.perturb_time_limit_s = 0.0;
  return options;
}

TEST(GeometryTetrahedralizeTest, BoxIsFilledWithGoodPositiveTets) {
  const SurfaceMesh box = testing::box(0.05, 0.03, 0.02);
  const TetMesh mesh = tetrahedralize(box, exude_only(0.01), "box");
  const TetQuality quality = tet_quality(mesh, kMinDihedralDeg);
  EXPECT_EQ(quality.inverted_count, 0);
  EXPECT_EQ(quality.sliver_count, 0);
  EXPECT_GT(quality.min_dihedral_deg, kMinDihedralDeg);
  // Sharp edges are protected, so the planar box is reproduced up to round-off.
  EXPECT_NEAR(quality.total_volume / surface_volume(box), 1.0, 1e-6);
  // The tets' boundary is a closed outward surface of the same volume (an exact invariant).
  EXPECT_NEAR(surface_volume(boundary_surface(mesh)), quality.total_volume, 1e-15);
}

TEST(GeometryTetrahedralizeTest, SphereVolumeApproachesTheSurfaceVolume) {
  const SurfaceMesh sphere = testing::uv_sphere(0.05, 24, 48);
  const TetMesh mesh = tetrahedralize(sphere, exude_only(0.012), "sphere");
  const TetQuality quality = tet_quality(mesh);
  EXPECT_EQ(quality.inverted_count, 0);
  EXPECT_GT(quality.min_dihedral_deg, kMinDihedralDeg);
  // Mesh_3 approximates a curved surface within facet_distance = 0.1 * edge: a relative volume
  // error of at most about 3 * facet_distance / radius.
  EXPECT_NEAR(quality.total_volume / surface_volume(sphere), 1.0, 3 * 0.1 * 0.012 / 0.05);
}

TEST(GeometryTetrahedralizeTest, SameSeedSameMesh) {
  const SurfaceMesh sphere = testing::uv_sphere(0.05, 12, 24);
  const TetMesh a = tetrahedralize(sphere, exude_only(0.02));
  const TetMesh b = tetrahedralize(sphere, exude_only(0.02));
  EXPECT_EQ(a.vertices, b.vertices);
  EXPECT_EQ(a.tets, b.tets);
}

TEST(GeometryTetrahedralizeTest, RefusesOpenFlatOrNonsenseInput) {
  SurfaceMesh open = testing::box(0.05, 0.05, 0.05);
  open.triangles.conservativeResize(11, 3);
  TetOptions options = exude_only(0.01);
  EXPECT_THROW(tetrahedralize(open, options), std::invalid_argument);

  SurfaceMesh inward = testing::box(0.05, 0.05, 0.05);
  inward.triangles.col(1).swap(inward.triangles.col(2));
  EXPECT_THROW(tetrahedralize(inward, options), std::invalid_argument);

  options.edge_length = 0.0;
  EXPECT_THROW(tetrahedralize(testing::box(0.05, 0.05, 0.05), options), std::invalid_argument);
}

}  // namespace
}  // namespace grip::geometry
