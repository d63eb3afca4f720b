// The boundary of a tet mesh: which faces, their orientation, the vertex map.
#include "src/geometry/boundary_surface.hpp"

#include <gtest/gtest.h>

#include "src/geometry/mesh_measures.hpp"

namespace grip::geometry {
namespace {

TEST(GeometryBoundarySurfaceTest, TwoTetsShareOneHiddenFace) {
  TetMesh mesh;
  mesh.vertices.resize(6, 3);
  mesh.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 7, 7, 7;  // vertex 5 unused
  mesh.tets.resize(2, 4);
  mesh.tets << 0, 1, 2, 3, 0, 2, 1, 4;  // both positive, sharing face (0, 1, 2)
  Eigen::VectorXi map;
  const SurfaceMesh surface = boundary_surface(mesh, &map);
  EXPECT_EQ(surface.triangles.rows(), 6);
  EXPECT_EQ(surface.vertices.rows(), 5);
  EXPECT_EQ(map, (Eigen::VectorXi(5) << 0, 1, 2, 3, 4).finished());
  // Outward faces enclose exactly the two tets' volume.
  EXPECT_NEAR(surface_volume(surface), 2.0 / 6.0, 1e-15);
}

}  // namespace
}  // namespace grip::geometry
