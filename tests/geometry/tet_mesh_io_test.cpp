// Tet meshes from other tools: each format read back exactly, and each class of bad mesh
// refused with its own message.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "src/geometry/mesh_io.hpp"
#include "src/geometry/tet_mesh_io.hpp"

namespace grip::geometry {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "grip_tet_mesh_io_test";
  fs::create_directories(dir);
  return dir / name;
}

fs::path write(const std::string& name, const std::string& text) {
  const fs::path file = scratch(name);
  std::ofstream(file) << text;
  return file;
}

// A unit cube (scaled to 2 cm) cut into five positive tets: the centre tet and four corners.
TetMesh cube() {
  TetMesh mesh;
  mesh.vertices.resize(8, 3);
  for (int i = 0; i < 8; ++i) {
    mesh.vertices.row(i) << 0.02 * (i & 1), 0.02 * ((i >> 1) & 1), 0.02 * ((i >> 2) & 1);
  }
  mesh.tets.resize(5, 4);
  mesh.tets << 1, 2, 4, 7,  //
      0, 1, 2, 4,           //
      3, 2, 1, 7,           //
      5, 4, 7, 1,           //
      6, 7, 4, 2;
  return mesh;
}

std::string points_text(const TetMesh& mesh, int first_tag, bool tagged) {
  std::ostringstream out;
  out.precision(17);
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
    if (tagged) out << v + first_tag << ' ';
    out << mesh.vertices(v, 0) << ' ' << mesh.vertices(v, 1) << ' ' << mesh.vertices(v, 2) << '\n';
  }
  return out.str();
}

std::string vtk_42(const TetMesh& mesh) {
  std::ostringstream out;
  out << "# vtk DataFile Version 4.2\nfinger\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS "
      << mesh.vertices.rows() << " double\n"
      << points_text(mesh, 0, false) << "CELLS " << mesh.tets.rows() + 1 << ' '
      << 5 * mesh.tets.rows() + 4 << '\n';
  for (Eigen::Index t = 0; t < mesh.tets.rows(); ++t) out << "4 " << mesh.tets.row(t) << '\n';
  out << "3 0 1 2\nCELL_TYPES " << mesh.tets.rows() + 1 << '\n';
  for (Eigen::Index t = 0; t < mesh.tets.rows(); ++t) out << "10\n";
  out << "5\nCELL_DATA " << mesh.tets.rows() + 1 << "\nSCALARS id int 1\n";
  return out.str();
}

std::string vtk_51(const TetMesh& mesh) {
  std::ostringstream out;
  out << "# vtk DataFile Version 5.1\nfinger\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS "
      << mesh.vertices.rows() << " double\n"
      << points_text(mesh, 0, false) << "METADATA\nINFORMATION 0\n\nCELLS " << mesh.tets.rows() + 1
      << ' ' << 4 * mesh.tets.rows() << "\nOFFSETS vtktypeint64\n";
  for (Eigen::Index t = 0; t <= mesh.tets.rows(); ++t) out << 4 * t << '\n';
  out << "CONNECTIVITY vtktypeint64\n";
  for (Eigen::Index t = 0; t < mesh.tets.rows(); ++t) out << mesh.tets.row(t) << '\n';
  out << "CELL_TYPES " << mesh.tets.rows() << '\n';
  for (Eigen::Index t = 0; t < mesh.tets.rows(); ++t) out << "10\n";
  return out.str();
}

// Gmsh 4.1 with a surface triangle block and parametric surface nodes, tags from 11.
std::string msh_41(const TetMesh& mesh) {
  std::ostringstream out;
  out.precision(17);
  const Eigen::Index n = mesh.vertices.rows();
  out << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n3 1 \"finger\"\n"
         "$EndPhysicalNames\n$Nodes\n2 "
      << n << " 11 " << 10 + n << "\n2 1 1 2\n11\n12\n";
  for (Eigen::Index v = 0; v < 2; ++v) out << mesh.vertices.row(v) << " 0.5 0.5\n";
  out << "3 1 0 " << n - 2 << '\n';
  for (Eigen::Index v = 2; v < n; ++v) out << v + 11 << '\n';
  for (Eigen::Index v = 2; v < n; ++v) out << mesh.vertices.row(v) << '\n';
  out << "$EndNodes\n$Elements\n2 " << mesh.tets.rows() + 1 << " 1 " << mesh.tets.rows() + 1
      << "\n2 1 2 1\n1 11 12 13\n3 1 4 " << mesh.tets.rows() << '\n';
  for (Eigen::Index t = 0; t < mesh.tets.rows(); ++t) {
    out << t + 2;
    for (int c = 0; c < 4; ++c) out << ' ' << mesh.tets(t, c) + 11;
    out << '\n';
  }
  out << "$EndElements\n";
  return out.str();
}

std::string medit(const TetMesh& mesh) {
  std::ostringstream out;
  out.precision(17);
  out << "MeshVersionFormatted 2\n# a comment\nDimension 3\nVertices\n"
      << mesh.vertices.rows() << '\n';
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) out << mesh.vertices.row(v) << " 0\n";
  out << "Triangles\n1\n1 2 3 5\nTetrahedra\n" << mesh.tets.rows() << '\n';
  for (Eigen::Index t = 0; t < mesh.tets.rows(); ++t) {
    for (int c = 0; c < 4; ++c) out << mesh.tets(t, c) + 1 << ' ';
    out << "1\n";
  }
  out << "End\n";
  return out.str();
}

void expect_same(const TetMesh& read, const TetMesh& expected) {
  EXPECT_EQ(read.vertices, expected.vertices);
  EXPECT_EQ(read.tets, expected.tets);
}

TEST(GeometryTetMeshIo, EveryFormatReadsBackTheTetsExactly) {
  const TetMesh mesh = cube();
  expect_same(read_tet_mesh(write("a.vtk", vtk_42(mesh))), mesh);
  expect_same(read_tet_mesh(write("b.VTK", vtk_51(mesh))), mesh);
  expect_same(read_tet_mesh(write("c.msh", msh_41(mesh))), mesh);
  expect_same(read_tet_mesh(write("d.mesh", medit(mesh))), mesh);
  write_msh(scratch("e.msh"), mesh);  // grip's own Gmsh 2.2
  expect_same(read_tet_mesh(scratch("e.msh")), mesh);
}

TEST(GeometryTetMeshIo, VerticesNoTetUsesAreDropped) {
  TetMesh mesh = cube();
  mesh.tets.conservativeResize(1, 4);  // the centre tet: vertices 1, 2, 4, 7
  const TetMesh read = read_tet_mesh(write("one.mesh", medit(mesh)));
  ASSERT_EQ(read.vertices.rows(), 4);
  EXPECT_EQ(read.vertices.row(3), mesh.vertices.row(7));
  EXPECT_EQ(read.tets.row(0), Eigen::RowVector4i(0, 1, 2, 3));
}

void expect_refused(const fs::path& file, const std::string& message) {
  try {
    read_tet_mesh(file);
    ADD_FAILURE() << file << " was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
  }
}

TEST(GeometryTetMeshIo, BadFilesAreOneMessageNamingTheFileAndTheFix) {
  const std::string cube_msh = msh_41(cube());
  expect_refused(write("f.stl", "solid"), "use .vtk (legacy VTK), .msh (Gmsh) or .mesh (MEDIT)");
  expect_refused(scratch("missing.msh"), "no such file");
  expect_refused(write("binary.msh", "$MeshFormat\n4.1 1 8\n"), "save it as ASCII");
  expect_refused(write("old.msh", "$MeshFormat\n4.0 0 8\n$EndMeshFormat\n"), "save as 4.1 or 2.2");
  expect_refused(write("tet10.msh",
                       "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 0 0 0\n"
                       "$EndNodes\n$Elements\n1\n1 11 0 1 1 1 1 1 1 1 1 1 1\n"),
                 "first-order mesh");
  expect_refused(write("huge.mesh", "MeshVersionFormatted 1\nVertices\n99999999999\n"),
                 "more than the file holds");
  expect_refused(write("dangling.mesh",
                       "MeshVersionFormatted 1\nVertices\n1\n0 0 0 0\n"
                       "Tetrahedra\n1\n1 2 3 4 0\nEnd\n"),
                 "refers to vertex 2");
  expect_refused(write("surface.mesh",
                       "MeshVersionFormatted 1\nVertices\n3\n0 0 0 0\n1 0 0 0\n"
                       "0 1 0 0\nTriangles\n1\n1 2 3 0\nEnd\n"),
                 "no 4-node tetrahedron");
  expect_refused(write("nan.vtk",
                       "# vtk DataFile Version 4.2\nt\nASCII\nDATASET "
                       "UNSTRUCTURED_GRID\nPOINTS 1 double\nnan 0 0\n"),
                 "not a finite number");
  expect_refused(write("binary.vtk", "# vtk DataFile Version 4.2\nt\nBINARY\n"),
                 "save it as ASCII");
  expect_refused(write("cut.msh", cube_msh.substr(0, cube_msh.size() / 2)), "the file ends before");
}

void expect_bad_body(TetMesh mesh, const std::string& message) {
  try {
    check_soft_body_mesh(mesh, "finger.msh");
    ADD_FAILURE() << "accepted; expected: " << message;
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("finger.msh"), std::string::npos) << e.what();
  }
}

TEST(GeometryTetMeshIo, ASoftBodyIsCheckedAndOrientedPositively) {
  TetMesh good = cube();
  check_soft_body_mesh(good, "finger.msh");
  EXPECT_EQ(good.tets, cube().tets);

  TetMesh negative = cube();
  negative.tets.col(0).swap(negative.tets.col(1));  // every tet flipped: another convention
  check_soft_body_mesh(negative, "finger.msh");
  TetMesh oriented = cube();
  oriented.tets.col(0).swap(oriented.tets.col(1));
  oriented.tets.col(1).swap(oriented.tets.col(2));
  EXPECT_EQ(negative.tets, oriented.tets);

  TetMesh mixed = cube();
  mixed.tets.row(0).head<2>().reverseInPlace();
  expect_bad_body(mixed, "1 of 5 tets are inverted");

  TetMesh flat = cube();
  // The centre tet's fourth corner onto its opposite face.
  flat.vertices.row(7) = (flat.vertices.row(1) + flat.vertices.row(2) + flat.vertices.row(4)) / 3;
  expect_bad_body(flat, "tet 0 is degenerate");

  TetMesh millimetres = cube();
  millimetres.vertices *= 1000.0;
  expect_bad_body(millimetres, "are its units millimetres?");

  TetMesh pinched = cube();  // the corner tet at 0 and a tet outside the cube at vertex 1
  pinched.vertices.conservativeResize(11, 3);
  pinched.vertices.row(8) = pinched.vertices.row(1) + Eigen::RowVector3d(0.02, 0.0, 0.0);
  pinched.vertices.row(9) = pinched.vertices.row(1) + Eigen::RowVector3d(0.0, -0.02, 0.0);
  pinched.vertices.row(10) = pinched.vertices.row(1) + Eigen::RowVector3d(0.0, 0.0, -0.02);
  pinched.tets.resize(2, 4);
  pinched.tets << 0, 1, 2, 4, 1, 8, 9, 10;
  expect_bad_body(pinched, "tets meet at a vertex only");

  TetMesh hinged = cube();  // two tets along one edge only (1-7)
  hinged.tets.resize(2, 4);
  hinged.tets << 3, 2, 1, 7, 5, 4, 7, 1;
  expect_bad_body(hinged, "an edge lies on 4 boundary faces");
}

}  // namespace
}  // namespace grip::geometry
