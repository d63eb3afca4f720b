// Tet quality figures against closed-form values for the regular and the corner tetrahedron.
#include "src/geometry/tet_quality.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>

namespace grip::geometry {
namespace {

constexpr double kDegree = 180.0 / std::numbers::pi;

TEST(GeometryTetQualityTest, RegularTetHasDihedralArccosOneThird) {
  TetMesh mesh;
  mesh.vertices.resize(4, 3);
  mesh.vertices << 1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1;
  mesh.tets.resize(1, 4);
  mesh.tets << 0, 1, 2, 3;
  if ((mesh.vertices.row(1) - mesh.vertices.row(0))
          .cross(mesh.vertices.row(2) - mesh.vertices.row(0))
          .dot(mesh.vertices.row(3) - mesh.vertices.row(0)) < 0) {
    std::swap(mesh.tets(0, 2), mesh.tets(0, 3));
  }
  const TetQuality quality = tet_quality(mesh);
  EXPECT_NEAR(quality.min_dihedral_deg, std::acos(1.0 / 3.0) * kDegree, 1e-12);
  EXPECT_NEAR(quality.max_dihedral_deg, std::acos(1.0 / 3.0) * kDegree, 1e-12);
  EXPECT_NEAR(quality.total_volume, 8.0 / 3.0, 1e-14);  // edge 2*sqrt(2): a^3 / (6 sqrt 2)
  EXPECT_EQ(quality.inverted_count, 0);
  EXPECT_EQ(quality.sliver_count, 0);
}

TEST(GeometryTetQualityTest, CornerTetAnglesAndInversion) {
  TetMesh mesh;
  mesh.vertices.resize(4, 3);
  mesh.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  mesh.tets.resize(2, 4);
  mesh.tets << 0, 1, 2, 3, 0, 2, 1, 3;  // the second is the first, inverted
  const TetQuality quality = tet_quality(mesh);
  // Edges on the axes meet at 90 degrees; edges of the slanted face at acos(1/sqrt(3)).
  EXPECT_NEAR(quality.min_dihedral_deg, std::acos(1.0 / std::sqrt(3.0)) * kDegree, 1e-12);
  EXPECT_NEAR(quality.max_dihedral_deg, 90.0, 1e-12);
  EXPECT_NEAR(quality.min_volume, -1.0 / 6.0, 1e-15);
  EXPECT_NEAR(quality.total_volume, 0.0, 1e-15);
  EXPECT_EQ(quality.inverted_count, 1);
}

TEST(GeometryTetQualityTest, FlatTetIsASliver) {
  TetMesh mesh;
  mesh.vertices.resize(4, 3);
  mesh.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.3, 0.3, 0.01;
  mesh.tets.resize(1, 4);
  mesh.tets << 0, 1, 2, 3;
  const TetQuality quality = tet_quality(mesh, 5.0);
  EXPECT_LT(quality.min_dihedral_deg, 5.0);
  EXPECT_EQ(quality.sliver_count, 1);
  EXPECT_EQ(quality.inverted_count, 0);
}

}  // namespace
}  // namespace grip::geometry
