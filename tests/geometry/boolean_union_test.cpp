// The union of two solids: its volume, and its numbering fixed by the geometry alone.
#include <gtest/gtest.h>

#include "src/geometry/boolean_union.hpp"
#include "src/geometry/mesh_measures.hpp"
#include "tests/geometry/test_meshes.hpp"

namespace grip::geometry {
namespace {

SurfaceMesh shifted(SurfaceMesh mesh, double x, double y, double z) {
  mesh.vertices.rowwise() += Eigen::RowVector3d(x, y, z);
  return mesh;
}

// The same surface with its vertices and triangles numbered otherwise: vertices reversed,
// triangles reversed, each started at its second corner (orientation kept).
SurfaceMesh renumbered(const SurfaceMesh& mesh) {
  const Eigen::Index n = mesh.vertices.rows();
  SurfaceMesh out;
  out.vertices = mesh.vertices.colwise().reverse();
  out.triangles.resize(mesh.triangles.rows(), 3);
  for (Eigen::Index f = 0; f < mesh.triangles.rows(); ++f) {
    const Eigen::Index from = mesh.triangles.rows() - 1 - f;
    for (int c = 0; c < 3; ++c) {
      out.triangles(f, c) = static_cast<int>(n - 1 - mesh.triangles(from, (c + 1) % 3));
    }
  }
  return out;
}

TEST(GeometryBooleanUnionTest, TwoOverlappingBoxesMakeTheirUnionsVolume) {
  // 4 x 2 x 2 cm and 2 x 4 x 2 cm, the second raised 0.5 cm: 16 + 16 - 2 x 2 x 1.5 cm^3.
  const SurfaceMesh a = testing::box(0.02, 0.01, 0.01);
  const SurfaceMesh b = shifted(testing::box(0.01, 0.02, 0.01), 0.0, 0.0, 0.005);
  const SurfaceMesh u = boolean_union(a, b);
  EXPECT_NEAR(surface_volume(u), 26e-6, 1e-12);
}

// Corefinement numbers its output by where its boxes lie in memory; the union must not: the
// same operands numbered otherwise give the same union, vertex for vertex.
TEST(GeometryBooleanUnionTest, TheUnionIsNumberedByItsGeometryAlone) {
  const SurfaceMesh a = testing::box(0.02, 0.01, 0.01);
  const SurfaceMesh b = shifted(testing::uv_sphere(0.012, 10, 20), 0.02, 0.0, 0.0);
  const SurfaceMesh first = boolean_union(a, b);
  const SurfaceMesh second = boolean_union(renumbered(a), renumbered(b));
  const SurfaceMesh swapped = boolean_union(b, a);
  EXPECT_EQ(first.vertices, second.vertices);
  EXPECT_EQ(first.triangles, second.triangles);
  EXPECT_EQ(first.vertices, swapped.vertices);
  EXPECT_EQ(first.triangles, swapped.triangles);
  EXPECT_NEAR(surface_volume(first), surface_volume(swapped), 1e-15);
}

}  // namespace
}  // namespace grip::geometry
