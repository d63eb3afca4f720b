// Reading and writing mesh files: round trips, every input format, and clear errors.
#include "src/geometry/mesh_io.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/geometry/test_meshes.hpp"

namespace grip::geometry {
namespace {

namespace fs = std::filesystem;

class GeometryMeshIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("grip_mesh_io_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write(const std::string& name, const std::string& text) {
    const fs::path file = dir_ / name;
    std::ofstream(file) << text;
    return file;
  }
  static std::string slurp(const fs::path& file) {
    std::ifstream in(file);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }
  fs::path dir_;
};

TEST_F(GeometryMeshIoTest, ObjRoundTripIsExact) {
  SurfaceMesh mesh = testing::box(0.1, 0.2, 0.3);
  mesh.vertices(0, 0) = 0.1234567890123456789;
  write_obj(dir_ / "box.obj", mesh);
  const SurfaceMesh back = read_surface_mesh(dir_ / "box.obj");
  EXPECT_EQ(back.vertices, mesh.vertices);
  EXPECT_EQ(back.triangles, mesh.triangles);
}

TEST_F(GeometryMeshIoTest, ReadsOffPlyAndStlAndMergesStlCorners) {
  const std::string off =
      "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  const SurfaceMesh from_off = read_surface_mesh(write("tet.off", off));
  EXPECT_EQ(from_off.vertices.rows(), 4);
  EXPECT_EQ(from_off.triangles.rows(), 4);

  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
  const SurfaceMesh from_ply = read_surface_mesh(write("quad.PLY", ply));
  EXPECT_EQ(from_ply.vertices.rows(), 4);
  EXPECT_EQ(from_ply.triangles.rows(), 2) << "a quad is split into two triangles";

  // Two ASCII STL facets sharing an edge: 6 corners, 4 distinct points.
  const std::string stl =
      "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\n"
      "endloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 1 0\n"
      "vertex 0 1 0\nendloop\nendfacet\nendsolid t\n";
  const SurfaceMesh from_stl = read_surface_mesh(write("two.stl", stl));
  EXPECT_EQ(from_stl.vertices.rows(), 4);
  EXPECT_EQ(from_stl.triangles.rows(), 2);
}

TEST_F(GeometryMeshIoTest, MissingFileErrorNamesIt) {
  try {
    read_surface_mesh(dir_ / "nothing.obj");
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("nothing.obj"), std::string::npos) << e.what();
  }
}

TEST_F(GeometryMeshIoTest, EmptyFileIsAnError) {
  const fs::path file = write("empty.obj", "");
  try {
    read_surface_mesh(file);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("empty.obj' is empty"), std::string::npos) << e.what();
  }
}

TEST_F(GeometryMeshIoTest, UnreadableContentIsAnError) {
  const fs::path file = write("garbage.off", "this is not an OFF file\n\x01\x02\x03");
  EXPECT_THROW(read_surface_mesh(file), std::runtime_error);
  const fs::path vertices_only = write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  EXPECT_THROW(read_surface_mesh(vertices_only), std::runtime_error);
}

// Found by fuzz/fuzz_mesh: 18 bytes that made CGAL allocate 2.4 GB for the vertices declared;
// and again with a comment between the keyword and the counts, which CGAL skips.
TEST_F(GeometryMeshIoTest, OffCountsBeyondTheFileSizeAreAnError) {
  for (const std::string text : {"OFF\n99999999 1 0\n", "# c\n4 99999999 0\n0 0 0\n",
                                 "3OFF \n\n#\n99808000 1 2\n", "nOFF # c\n3 # d\n99808000 1 2\n"}) {
    try {
      read_surface_mesh(write("huge.off", text));
      ADD_FAILURE() << "no error for " << text;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("more than its"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(read_surface_mesh(write("tet.off",
                                    "OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
                                    "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"))
                .triangles.rows(),
            4);
}

// Found by fuzz/fuzz_mesh: CGAL's PLY reader indexed an empty element list.
TEST_F(GeometryMeshIoTest, PlyPropertyBeforeAnyElementIsAnError) {
  const fs::path file = write("property_first.ply",
                              "ply\nformat ascii 1.0\nproperty float x\nelement vertex 1\n"
                              "end_header\n0\n");
  try {
    read_surface_mesh(file);
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("property before any element"), std::string::npos)
        << e.what();
  }
}

// read_surface_mesh's error message for `file`, or "no error".
std::string error(const fs::path& file) {
  try {
    read_surface_mesh(file);
  } catch (const std::runtime_error& e) {
    return std::string(e.what());
  }
  return std::string("no error");
}

// Found by fuzz/fuzz_mesh: a face index outside the vertices read past them, and a PLY element
// count of -1 kept CGAL's reader going for ever.
TEST_F(GeometryMeshIoTest, FaceIndicesAndElementCountsOutOfRangeAreErrors) {
  EXPECT_NE(
      error(write("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 0 2\n")).find("refers to vertex"),
      std::string::npos);
  EXPECT_NE(error(write("past.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n")).find("vertex 4 of 3"),
            std::string::npos);
  EXPECT_NE(error(write("negative.ply",
                        "ply\nformat ascii 1.0\nelement vertex -1\n"
                        "property float x\nend_header\n"))
                .find("'-1' vertex elements"),
            std::string::npos);
  // Integer coordinates made CGAL's PLY reader call through a null pointer.
  EXPECT_NE(error(write("int.ply",
                        "ply\nformat ascii 1.0\nelement vertex 3\nproperty int x\n"
                        "property float y\nproperty float z\nend_header\n"))
                .find("vertex coordinate 'x' is of type 'int'"),
            std::string::npos);
  // Found by fuzz_mesh: a list-typed coordinate went through the same null pointer.
  EXPECT_NE(error(write("list.ply",
                        "ply\nformat ascii 1.0\nelement vertex 3\nproperty list uchar float x\n"
                        "property float y\nproperty float z\nend_header\n"))
                .find("vertex coordinate 'x' is of type 'list'"),
            std::string::npos);
  // A face of 2^61 corners made CGAL's OFF reader throw std::length_error.
  EXPECT_NE(error(write("corners.off",
                        "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n"
                        "2305843009213693952 0 1 2\n"))
                .find("face 1 declares 2305843009213693952 corners but its line lists 3 numbers"),
            std::string::npos);
}

// A binary OFF file (big-endian int32 and float32) of the unit tetrahedron's vertices and
// faces, each face with `corners` as its count.
std::string binary_off(std::int32_t vertices, std::int32_t faces, std::int32_t corners,
                       std::int32_t edges = 0) {
  std::string bytes = "OFF BINARY\n";
  const auto put = [&](std::uint32_t word) {
    for (int shift = 24; shift >= 0; shift -= 8) bytes += static_cast<char>(word >> shift);
  };
  put(static_cast<std::uint32_t>(vertices));
  put(static_cast<std::uint32_t>(faces));
  put(static_cast<std::uint32_t>(edges));
  const float one = 1.0f;
  std::uint32_t one_bits = 0;
  std::memcpy(&one_bits, &one, sizeof one);
  for (const std::array<std::uint32_t, 3> v : {std::array<std::uint32_t, 3>{0, 0, 0},
                                               {one_bits, 0, 0},
                                               {0, one_bits, 0},
                                               {0, 0, one_bits}}) {
    for (const std::uint32_t c : v) put(c);
  }
  for (const std::array<std::uint32_t, 3> f :
       {std::array<std::uint32_t, 3>{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}) {
    put(static_cast<std::uint32_t>(corners));
    for (const std::uint32_t i : f) put(i);
  }
  return bytes;
}

// Found by fuzz/fuzz_mesh: an ASCII face of 97,999,999,998,080 corners made CGAL size the face
// by that count (std::bad_alloc, or an out-of-memory report under ASan). Binary OFF counts and
// corner counts were not checked at all, nor any edge count. Each is refused before CGAL
// reads it.
TEST_F(GeometryMeshIoTest, OffFaceCornerCountsAndBinaryCountsAreCheckedBeforeAllocating) {
  const fs::path ascii = write("corners.off",
                               "OFF\n4 2 0\n0 0 0\n1 0 0 # a comment\n0 1 0\n\n0 0 1\n"
                               "3 0 2 1\n# a comment\n97999999998080 0 1 3\n");
  EXPECT_EQ(error(ascii), "cannot read '" + ascii.string() +
                              "': face 2 declares 97999999998080 corners but its line lists 3 "
                              "numbers after the count");
  // Found by fuzz_mesh: a vertex line "3 0-3" holds three numbers (CGAL reads a vertex per line),
  // so the next line is a face, of 21111111111 corners.
  EXPECT_NE(error(write("vertex_line.off",
                        "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0-3\n"
                        "21111111111 0 1 2\n"))
                .find("face 1 declares 21111111111 corners but its line lists 3 numbers"),
            std::string::npos);
  // Found by fuzz_mesh: with no vertex the face was not checked.
  EXPECT_NE(error(write("no_vertex.off", "OFF\n\n0 1 0\n97999999-998080 0 1 2\n"))
                .find("face 1 declares 97999999 corners but its line lists 4 numbers"),
            std::string::npos);
  EXPECT_NE(error(write("negative.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n-1 0 1 2\n"))
                .find("face 1 declares -1 corners"),
            std::string::npos);

  EXPECT_EQ(read_surface_mesh(write("tet_binary.off", binary_off(4, 4, 3))).triangles.rows(), 4);
  const fs::path counts = write("counts.off", binary_off(99999999, 4, 3));
  EXPECT_EQ(error(counts), "cannot read '" + counts.string() +
                               "': its binary header declares 99999999 vertices and 4 faces, not "
                               "counts its 135 bytes can hold");
  EXPECT_NE(error(write("negative_binary.off", binary_off(4, -4, 3))).find("-4 faces"),
            std::string::npos);
  // CGAL doubles the edge count in an int (signed overflow, found by fuzz_mesh in binary OFF).
  EXPECT_NE(error(write("edges.off", "OFF\n4 4 2000000000\n0 0 0\n")).find("2000000000 edges"),
            std::string::npos);
  EXPECT_NE(error(write("edges_binary.off", binary_off(4, 4, 3, 1919774464)))
                .find("its header declares 1919774464 edges, not a count its 135 bytes can hold"),
            std::string::npos);
  // Found by fuzz_mesh: CGAL read a face count cut short by the end of the file as if whole.
  const std::string whole = binary_off(4, 4, 3);
  EXPECT_NE(error(write("cut_binary.off", whole.substr(0, 11 + 12 + 48 + 2)))
                .find("the file ends before the corner count of face 1 of 4"),
            std::string::npos);
  const fs::path corners = write("corners_binary.off", binary_off(4, 4, 2000000000));
  EXPECT_EQ(error(corners), "cannot read '" + corners.string() +
                                "': face 1 declares 2000000000 corners, more than the 60 bytes "
                                "after it can hold");
  // Binary variants whose vertices carry colours, normals or more coordinates are refused whole:
  // their faces cannot be found without parsing every vertex's extras as CGAL does.
  for (const std::string prefix : {"C", "N", "ST", "4", "STCN"}) {
    const fs::path variant = write(prefix + "_binary.off", prefix + whole);
    EXPECT_EQ(error(variant), "cannot read '" + variant.string() +
                                  "': binary OFF with per-vertex colours, normals, texture "
                                  "coordinates or other than 3 coordinates is not read; write it "
                                  "as plain 'OFF BINARY' or as ASCII OFF")
        << prefix;
  }
}

TEST_F(GeometryMeshIoTest, UnknownExtensionIsAnError) {
  const fs::path file = write("mesh.xyz", "v 0 0 0\n");
  try {
    read_surface_mesh(file);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(".obj, .stl, .ply or .off"), std::string::npos);
  }
}

TEST_F(GeometryMeshIoTest, MshAndVtuHoldEveryNodeAndTet) {
  TetMesh mesh;
  mesh.vertices.resize(5, 3);
  mesh.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1;
  mesh.tets.resize(2, 4);
  mesh.tets << 0, 1, 2, 3, 1, 2, 3, 4;
  write_msh(dir_ / "m.msh", mesh);
  const std::string msh = slurp(dir_ / "m.msh");
  EXPECT_NE(msh.find("$MeshFormat\n2.2 0 8\n"), std::string::npos);
  EXPECT_NE(msh.find("$Nodes\n5\n"), std::string::npos);
  EXPECT_NE(msh.find("$Elements\n2\n1 4 2 1 1 1 2 3 4\n2 4 2 1 1 2 3 4 5\n"), std::string::npos);

  Eigen::VectorXd stress(2);
  stress << 1.5, 2.5;
  write_vtu(dir_ / "m.vtu", mesh, {{"stress", stress}});
  const std::string vtu = slurp(dir_ / "m.vtu");
  EXPECT_NE(vtu.find("NumberOfPoints=\"5\" NumberOfCells=\"2\""), std::string::npos);
  EXPECT_NE(vtu.find("Name=\"stress\""), std::string::npos);
  EXPECT_NE(vtu.find("1.5\n2.5\n"), std::string::npos);
  EXPECT_THROW(write_vtu(dir_ / "bad.vtu", mesh, {{"stress", Eigen::VectorXd(3)}}),
               std::invalid_argument);
}

TEST_F(GeometryMeshIoTest, UnwritableFolderIsAnError) {
  EXPECT_THROW(write_obj(dir_ / "no" / "such" / "dir.obj", testing::box(1, 1, 1)),
               std::runtime_error);
}

}  // namespace
}  // namespace grip::geometry
