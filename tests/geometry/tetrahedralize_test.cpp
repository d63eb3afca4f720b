// Mesh_3 tetrahedralization: valid orientation, quality bound, volume, determinism, and the
// inputs it refuses.
#include "src/geometry/tetrahedralize.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>

#include <cmath>
#include <numbers>
#include <set>
#include <utility>

#include "src/geometry/mesh_measures.hpp"
#include "tests/geometry/test_meshes.hpp"

namespace grip::geometry {
namespace {

// Perturbation and exudation aim at TetOptions::sliver_bound_deg (12 degrees); the bound
// promised leaves room for tets between protected sharp features, which they may not move.
constexpr double kMinDihedralDeg = 10.0;

TetOptions with_edge(double edge_length) {
  TetOptions options;
  options.edge_length = edge_length;
  return options;
}

// A ring torus about the z axis (major radius R, minor radius r), closed and outward.
SurfaceMesh torus(double major, double minor, int rings, int segments) {
  SurfaceMesh mesh;
  mesh.vertices.resize(rings * segments, 3);
  mesh.triangles.resize(2 * rings * segments, 3);
  for (int i = 0; i < rings; ++i) {
    const double u = 2.0 * std::numbers::pi * i / rings;
    for (int j = 0; j < segments; ++j) {
      const double v = 2.0 * std::numbers::pi * j / segments;
      mesh.vertices.row(i * segments + j) << (major + minor * std::cos(v)) * std::cos(u),
          (major + minor * std::cos(v)) * std::sin(u), minor * std::sin(v);
    }
  }
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < segments; ++j) {
      const int a = i * segments + j;
      const int b = ((i + 1) % rings) * segments + j;
      const int c = ((i + 1) % rings) * segments + (j + 1) % segments;
      const int d = i * segments + (j + 1) % segments;
      mesh.triangles.row(2 * a) << a, b, c;
      mesh.triangles.row(2 * a + 1) << a, c, d;
    }
  }
  return mesh;
}

TEST(GeometryTetrahedralizeTest, BoxIsFilledWithGoodPositiveTets) {
  const SurfaceMesh box = testing::box(0.05, 0.03, 0.02);
  const TetMesh mesh = tetrahedralize(box, with_edge(0.01), "box");
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
  const TetMesh mesh = tetrahedralize(sphere, with_edge(0.012), "sphere");
  const TetQuality quality = tet_quality(mesh);
  EXPECT_EQ(quality.inverted_count, 0);
  EXPECT_GT(quality.min_dihedral_deg, kMinDihedralDeg);
  // Mesh_3 approximates a curved surface within facet_distance = 0.1 * edge: a relative volume
  // error of at most about 3 * facet_distance / radius.
  EXPECT_NEAR(quality.total_volume / surface_volume(sphere), 1.0, 3 * 0.1 * 0.012 / 0.05);
}

// Mesh_3 seeds a smooth surface (no sharp features to protect) from rays shot from the bounding
// box centre; a torus's centre lies in its hole, and those seeds alone found no surface.
TEST(GeometryTetrahedralizeTest, TorusAroundItsBoundingBoxCentreIsFilled) {
  const SurfaceMesh ring = torus(0.05, 0.015, 48, 24);
  ASSERT_GT(surface_volume(ring), 0.0);
  const TetMesh mesh = tetrahedralize(ring, with_edge(0.01), "torus");
  const TetQuality quality = tet_quality(mesh, kMinDihedralDeg);
  EXPECT_EQ(quality.inverted_count, 0);
  EXPECT_EQ(quality.sliver_count, 0);
  // Inscribed within facet_distance = 0.1 * edge of the surface: a relative volume error of at
  // most about 2 * facet_distance / minor radius.
  EXPECT_NEAR(quality.total_volume / surface_volume(ring), 1.0, 2 * 0.1 * 0.01 / 0.015);
  // One solid ring: its boundary is a closed surface of genus 1, Euler characteristic 0.
  const SurfaceMesh boundary = boundary_surface(mesh);
  std::set<std::pair<int, int>> edges;
  for (Eigen::Index f = 0; f < boundary.triangles.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = boundary.triangles(f, k);
      const int b = boundary.triangles(f, (k + 1) % 3);
      edges.insert({std::min(a, b), std::max(a, b)});
    }
  }
  std::set<int> vertices(boundary.triangles.data(),
                         boundary.triangles.data() + boundary.triangles.size());
  EXPECT_EQ(static_cast<long>(vertices.size()) - static_cast<long>(edges.size()) +
                static_cast<long>(boundary.triangles.rows()),
            0);
}

// Depth of a point below the nearest face of a box centred on the origin (half extents `half`).
double box_depth(const Eigen::Vector3d& half, const Eigen::Vector3d& x) {
  return (half - x.cwiseAbs()).minCoeff();
}

// Mean edge length of the tets whose shallowest vertex lies in [from, to) below the box's
// surface.
double mean_edge_at_depth(const TetMesh& mesh, const Eigen::Vector3d& half, double from,
                          double to) {
  double sum = 0.0;
  int edges = 0;
  for (Eigen::Index t = 0; t < mesh.tets.rows(); ++t) {
    double shallowest = 1.0;
    for (int k = 0; k < 4; ++k) {
      shallowest = std::min(shallowest, box_depth(half, mesh.vertices.row(mesh.tets(t, k))));
    }
    if (shallowest < from || shallowest >= to) continue;
    for (int a = 0; a < 4; ++a) {
      for (int b = a + 1; b < 4; ++b) {
        sum += (mesh.vertices.row(mesh.tets(t, a)) - mesh.vertices.row(mesh.tets(t, b))).norm();
        ++edges;
      }
    }
  }
  return sum / edges;
}

// The largest circumradius of the tets with a vertex on the box's surface.
double largest_surface_circumradius(const TetMesh& mesh, const Eigen::Vector3d& half) {
  double largest = 0.0;
  for (Eigen::Index t = 0; t < mesh.tets.rows(); ++t) {
    Eigen::Vector3d v[4];
    bool on_surface = false;
    for (int k = 0; k < 4; ++k) {
      v[k] = mesh.vertices.row(mesh.tets(t, k)).transpose();
      on_surface = on_surface || box_depth(half, v[k]) < 1e-9;
    }
    if (!on_surface) continue;
    // The circumcentre c solves 2 (v_k - v_0) . c = |v_k|^2 - |v_0|^2, k = 1..3.
    Eigen::Matrix3d a;
    Eigen::Vector3d b;
    for (int k = 0; k < 3; ++k) {
      a.row(k) = 2.0 * (v[k + 1] - v[0]).transpose();
      b[k] = v[k + 1].squaredNorm() - v[0].squaredNorm();
    }
    largest = std::max(largest, (a.partialPivLu().solve(b) - v[0]).norm());
  }
  return largest;
}

// A graded mesh keeps the uniform mesh's tets at the surface and fills the inside with fewer,
// larger ones, of the same quality and the same volume.
TEST(GeometryTetrahedralizeTest, AGradedMeshKeepsTheSurfaceTetsAndCoarsensTheInside) {
  const Eigen::Vector3d half(0.06, 0.05, 0.045);
  const SurfaceMesh box = testing::box(half.x(), half.y(), half.z());
  const double edge = 0.008;
  const TetMesh uniform = tetrahedralize(box, with_edge(edge), "box");
  TetOptions graded_options = with_edge(edge);
  graded_options.interior_growth = kSoftObjectInteriorGrowth;
  const TetMesh graded = tetrahedralize(box, graded_options, "box");

  EXPECT_LT(graded.tets.rows(), 0.7 * uniform.tets.rows());
  const TetQuality quality = tet_quality(graded, kMinDihedralDeg);
  EXPECT_EQ(quality.inverted_count, 0);
  EXPECT_GT(quality.min_dihedral_deg, kMinDihedralDeg);
  EXPECT_NEAR(quality.total_volume / surface_volume(box), 1.0, 1e-6);
  // The tets with a vertex on the surface meet the uniform mesh's bound (a circumradius of one
  // edge, exceeded by 14 % at most in both meshes after sliver perturbation and exudation)
  // and are as long on average.
  EXPECT_LT(largest_surface_circumradius(uniform, half), 1.25 * edge);
  EXPECT_LT(largest_surface_circumradius(graded, half), 1.25 * edge);
  const double uniform_at_surface = mean_edge_at_depth(uniform, half, 0.0, 1e-9);
  EXPECT_NEAR(mean_edge_at_depth(graded, half, 0.0, 1e-9) / uniform_at_surface, 1.0, 0.1);
  // The uniform mesh's tets are the same size throughout; the graded mesh's 2 cm inside are
  // far larger.
  EXPECT_NEAR(mean_edge_at_depth(uniform, half, 0.02, 1.0) / uniform_at_surface, 1.0, 0.15);
  EXPECT_GT(mean_edge_at_depth(graded, half, 0.02, 1.0), 2.0 * uniform_at_surface);
}

TEST(GeometryTetrahedralizeTest, SameSeedSameMesh) {
  const SurfaceMesh sphere = testing::uv_sphere(0.05, 12, 24);
  const TetMesh a = tetrahedralize(sphere, with_edge(0.02));
  const TetMesh b = tetrahedralize(sphere, with_edge(0.02));
  EXPECT_EQ(a.vertices, b.vertices);
  EXPECT_EQ(a.tets, b.tets);
}

TEST(GeometryTetrahedralizeTest, RefusesOpenFlatOrNonsenseInput) {
  SurfaceMesh open = testing::box(0.05, 0.05, 0.05);
  open.triangles.conservativeResize(11, 3);
  TetOptions options = with_edge(0.01);
  EXPECT_THROW(tetrahedralize(open, options), std::invalid_argument);

  SurfaceMesh inward = testing::box(0.05, 0.05, 0.05);
  inward.triangles.col(1).swap(inward.triangles.col(2));
  EXPECT_THROW(tetrahedralize(inward, options), std::invalid_argument);

  options.edge_length = 0.0;
  EXPECT_THROW(tetrahedralize(testing::box(0.05, 0.05, 0.05), options), std::invalid_argument);
}

}  // namespace
}  // namespace grip::geometry
