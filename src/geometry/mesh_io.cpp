#include "src/geometry/mesh_io.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <new>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace grip::geometry {
namespace {

using Point = CGAL::Exact_predicates_inexact_constructions_kernel::Point_3;

std::ofstream open_for_writing(const std::filesystem::path& file) {
  std::ofstream out(file);
  if (!out) {
    throw std::runtime_error("cannot write '" + file.string() + "': " + std::strerror(errno) +
                             "; check that the folder exists and is writable");
  }
  out.precision(17);
  return out;
}

void finish_writing(std::ofstream& out, const std::filesystem::path& file) {
  out.close();
  if (!out) {
    throw std::runtime_error("writing '" + file.string() + "' failed (disk full?)");
  }
}

// Skips blanks and '#' comment lines, as CGAL's OFF reader does before a keyword, a vertex and a
// face.
void skip_off_comments(std::istream& in) {
  char c = 0;
  while (in >> c && c == '#') in.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
  if (in) in.unget();
}

// The reader's one error form: "cannot read 'FILE': PROBLEM".
[[noreturn]] void refuse_mesh(const std::filesystem::path& file, const std::string& problem) {
  throw std::runtime_error("cannot read '" + file.string() + "': " + problem);
}

// An OFF keyword as CGAL reads one (after blanks and '#' comments): its first character, then
// letters and digits; the character that ends it is consumed.
std::string off_keyword(std::istream& in) {
  skip_off_comments(in);
  std::string word;
  char c = 0;
  if (!in.get(c)) return word;
  word += c;
  while (in.get(c) && std::isalnum(static_cast<unsigned char>(c))) word += c;
  if (c == '\n') in.unget();  // BINARY's data start after the end of its line
  return word;
}

// CGAL doubles the edge count a header declares in an int: one past 2^30 overflows it.
void check_off_edges(const std::filesystem::path& file, long long edges, std::uintmax_t size) {
  if (edges < 0 || static_cast<std::uintmax_t>(edges) > size) {
    refuse_mesh(file, "its header declares " + std::to_string(edges) + " edges, not a count its " +
                          std::to_string(size) + " bytes can hold");
  }
}

std::int64_t big_endian_int32(std::istream& in) {
  unsigned char bytes[4] = {};
  in.read(reinterpret_cast<char*>(bytes), 4);
  const std::uint32_t value = (std::uint32_t{bytes[0]} << 24) | (std::uint32_t{bytes[1]} << 16) |
                              (std::uint32_t{bytes[2]} << 8) | std::uint32_t{bytes[3]};
  return static_cast<std::int32_t>(value);
}

// Binary OFF: big-endian int32 counts, float32 vertices, each face its corner count and
// indices (int32; CGAL's polygon soup reader reads no face color after them). CGAL sizes its arrays
// by the counts, and each face by its corner count, before reading them: every count is checked
// against the bytes that would hold it. Only plain 3D vertices (12 bytes each, "OFF BINARY") are
// read: with a prefix (C, N, ST, 4, n) a vertex carries a variable number of extra floats, so
// the faces could not be checked before CGAL sizes them.
void check_binary_off(const std::filesystem::path& file, std::istream& in, std::uintmax_t size,
                      bool plain, bool dimension) {
  in.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
  if (dimension) big_endian_int32(in);
  const std::int64_t vertices = big_endian_int32(in);
  const std::int64_t faces = big_endian_int32(in);
  const std::int64_t edges = big_endian_int32(in);
  if (!in) return;  // too short: CGAL's parser says so
  check_off_edges(file, edges, size);
  if (vertices < 0 || faces < 0 || static_cast<std::uintmax_t>(vertices) > size / 12 ||
      static_cast<std::uintmax_t>(faces) > size / 4) {
    refuse_mesh(file, "its binary header declares " + std::to_string(vertices) + " vertices and " +
                          std::to_string(faces) + " faces, not counts its " + std::to_string(size) +
                          " bytes can hold");
  }
  if (!plain) {
    refuse_mesh(file,
                "binary OFF with per-vertex colours, normals, texture coordinates or other "
                "than 3 coordinates is not read; write it as plain 'OFF BINARY' or as ASCII OFF");
  }
  in.seekg(vertices * 12, std::ios::cur);
  for (std::int64_t f = 0; f < faces; ++f) {
    const std::int64_t corners = big_endian_int32(in);
    // CGAL goes on with a count the end of the file cut short.
    if (!in) {
      refuse_mesh(file, "the file ends before the corner count of face " + std::to_string(f + 1) +
                            " of " + std::to_string(faces));
    }
    const auto at = static_cast<std::uintmax_t>(in.tellg());
    const std::uintmax_t left = size - std::min(size, at);
    if (corners < 0 || static_cast<std::uintmax_t>(corners) > left / 4) {
      refuse_mesh(file, "face " + std::to_string(f + 1) + " declares " + std::to_string(corners) +
                            " corners, more than the " + std::to_string(left) +
                            " bytes after it can hold");
    }
    in.seekg(corners * 4, std::ios::cur);
  }
}

// ASCII OFF vertices and faces are one line each (after blanks and comments); a face is its
// corner count, then that many vertex indices (and maybe a color). CGAL sizes a face by its
// count before it reads an index, so a count beyond the numbers its line lists is refused.
void check_ascii_off_faces(const std::filesystem::path& file, std::istream& in, long long vertices,
                           long long faces) {
  std::string line;
  for (long long v = 0; v < vertices; ++v) {
    skip_off_comments(in);
    if (!std::getline(in, line)) return;  // CGAL's parser says what is wrong
  }
  for (long long f = 1; f <= faces; ++f) {
    skip_off_comments(in);
    if (!std::getline(in, line)) return;
    std::istringstream words(line.substr(0, line.find('#')));
    std::vector<double> numbers;
    for (double x = 0; words >> x;) numbers.push_back(x);
    if (numbers.empty()) return;  // CGAL refuses the face
    const double corners = numbers.front();
    if (!(corners >= 0 && corners <= static_cast<double>(numbers.size() - 1))) {
      char count[32];
      const bool whole = corners == std::floor(corners) && std::abs(corners) < 1e19;
      std::snprintf(count, sizeof count, whole ? "%.0f" : "%g", corners);
      refuse_mesh(file, "face " + std::to_string(f) + " declares " + count +
                            " corners but its line lists " + std::to_string(numbers.size() - 1) +
                            " numbers after the count");
    }
  }
}

// CGAL sizes its arrays by an OFF header's counts before it reads a vertex, so a file of a few
// bytes that claims a billion vertices would make it allocate gigabytes. Each vertex takes at
// least 6 bytes ("0 0 0\n") and each face 2. Then each face's corner count is checked too.
void check_off(const std::filesystem::path& file, std::uintmax_t size) {
  std::ifstream in(file, std::ios::binary);
  const std::string keyword = off_keyword(in);
  long long dimension = 0;
  if (keyword.size() >= 3 && keyword.compare(keyword.size() - 3, 3, "OFF") == 0) {
    const std::string prefix = keyword.substr(0, keyword.size() - 3);
    const bool dimensional = prefix.find('n') != std::string::npos;  // nOFF: the dimension first
    const std::streampos header = in.tellg();
    if (off_keyword(in) == "BINARY") {
      return check_binary_off(file, in, size, prefix.empty(), dimensional);
    }
    in.clear();
    in.seekg(header);
    if (dimensional) {
      skip_off_comments(in);
      in >> dimension;
    }
  } else {  // no keyword: the counts from the start
    in.clear();
    in.seekg(0);
  }
  // As CGAL reads them, skipping '#' comments before each.
  long long vertices = 0, faces = 0, edges = 0;
  for (long long* count : {&vertices, &faces, &edges}) {
    skip_off_comments(in);
    in >> *count;
  }
  if (!in) return;  // not counts: CGAL's parser says what is wrong
  const std::string counts =
      std::to_string(vertices) + " vertices and " + std::to_string(faces) + " faces";
  if (vertices < 0 || faces < 0) {
    refuse_mesh(file, "its header declares " + counts + "; a count cannot be negative");
  }
  if (static_cast<std::uintmax_t>(vertices) > size / 6 ||
      static_cast<std::uintmax_t>(faces) > size / 2) {
    refuse_mesh(file, "its header declares " + counts + ", more than its " + std::to_string(size) +
                          " bytes can hold");
  }
  check_off_edges(file, edges, size);
  check_ascii_off_faces(file, in, vertices, faces);
}

// CGAL's PLY reader adds each property to the last element declared, reading past an empty
// array when a property comes first, and reads an element count as unsigned, so that -1 keeps
// it reading for ever: such headers are refused here. Each element takes at least one byte.
void check_ply_header(const std::filesystem::path& file, std::uintmax_t size) {
  std::ifstream in(file, std::ios::binary);
  std::string line;
  bool element = false;
  bool vertex = false;  // within the vertex element
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string word, name, count;
    words >> word;
    if (word == "end_header") return;
    if (word == "element") {
      element = true;
      words >> name >> count;
      vertex = name == "vertex";
      if (count.empty() || count.size() > 19 ||
          count.find_first_not_of("0123456789") != std::string::npos || std::stoull(count) > size) {
        refuse_mesh(file, "its header declares '" + count + "' " + name +
                              " elements, not a count its " + std::to_string(size) +
                              " bytes can hold");
      }
    }
    if (word == "property" && !element) {
      refuse_mesh(file, "its header declares a property before any element");
    }
    // CGAL reads a coordinate of another type through a null pointer.
    std::string type, property;
    words >> type >> property;
    if (type == "list") {  // property list COUNT_TYPE ITEM_TYPE NAME: a list coordinate too
      std::string item;
      words >> item >> property;
    }
    if (word == "property" && vertex && (property == "x" || property == "y" || property == "z") &&
        type != "float" && type != "double" && type != "float32" && type != "float64") {
      refuse_mesh(file, "vertex coordinate '" + property + "' is of type '" + type +
                            "'; use float or double");
    }
  }
}

}  // namespace

SurfaceMesh read_surface_mesh(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext != ".obj" && ext != ".stl" && ext != ".ply" && ext != ".off") {
    refuse_mesh(file, "unknown mesh format '" + ext + "'; use .obj, .stl, .ply or .off");
  }
  if (std::filesystem::is_directory(file)) {
    refuse_mesh(file, "is a directory, not a mesh file");
  }
  if (!std::filesystem::is_regular_file(file)) {
    refuse_mesh(file, "no such file");
  }
  const std::uintmax_t size = std::filesystem::file_size(file);
  if (size == 0) {
    throw std::runtime_error("mesh '" + file.string() + "' is empty: the file has no data");
  }
  if (ext == ".off") check_off(file, size);
  if (ext == ".ply") check_ply_header(file, size);
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  bool read = false;
  try {
    read = CGAL::IO::read_polygon_soup(file.string(), points, polygons);
  } catch (const std::length_error&) {  // CGAL sizes a face by the count the file gives
  } catch (const std::bad_alloc&) {
  }
  if (!read) {
    refuse_mesh(file, "not a valid " + ext.substr(1) + " mesh (the parser rejected it)");
  }
  for (const auto& polygon : polygons) {
    for (const std::size_t index : polygon) {
      if (index >= points.size()) {
        refuse_mesh(file, "a face refers to vertex " + std::to_string(index + 1) + " of " +
                              std::to_string(points.size()));
      }
    }
  }
  CGAL::Polygon_mesh_processing::merge_duplicate_points_in_polygon_soup(points, polygons);

  std::vector<std::array<int, 3>> triangles;
  for (const auto& polygon : polygons) {
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {
      triangles.push_back({static_cast<int>(polygon[0]), static_cast<int>(polygon[k]),
                           static_cast<int>(polygon[k + 1])});
    }
  }
  if (points.empty() || triangles.empty()) {
    throw std::runtime_error("mesh '" + file.string() +
                             "' is empty: it holds no triangle or polygon");
  }
  SurfaceMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto row = static_cast<Eigen::Index>(i);
    mesh.vertices.row(row) << points[i].x(), points[i].y(), points[i].z();
  }
  mesh.triangles.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const auto row = static_cast<Eigen::Index>(i);
    mesh.triangles.row(row) << triangles[i][0], triangles[i][1], triangles[i][2];
  }
  if (!mesh.vertices.allFinite()) {
    throw std::runtime_error("mesh '" + file.string() + "' has a NaN or infinite coordinate");
  }
  return mesh;
}

void write_obj(const std::filesystem::path& file, const SurfaceMesh& mesh) {
  std::ofstream out = open_for_writing(file);
  for (Eigen::Index i = 0; i < mesh.vertices.rows(); ++i) {
    out << "v " << mesh.vertices(i, 0) << ' ' << mesh.vertices(i, 1) << ' ' << mesh.vertices(i, 2)
        << '\n';
  }
  for (Eigen::Index i = 0; i < mesh.triangles.rows(); ++i) {
    out << "f " << mesh.triangles(i, 0) + 1 << ' ' << mesh.triangles(i, 1) + 1 << ' '
        << mesh.triangles(i, 2) + 1 << '\n';
  }
  finish_writing(out, file);
}

void write_msh(const std::filesystem::path& file, const TetMesh& mesh) {
  std::ofstream out = open_for_writing(file);
  out << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n" << mesh.vertices.rows() << '\n';
  for (Eigen::Index i = 0; i < mesh.vertices.rows(); ++i) {
    out << i + 1 << ' ' << mesh.vertices(i, 0) << ' ' << mesh.vertices(i, 1) << ' '
        << mesh.vertices(i, 2) << '\n';
  }
  out << "$EndNodes\n$Elements\n" << mesh.tets.rows() << '\n';
  for (Eigen::Index i = 0; i < mesh.tets.rows(); ++i) {
    out << i + 1 << " 4 2 1 1";
    for (int k = 0; k < 4; ++k) out << ' ' << mesh.tets(i, k) + 1;
    out << '\n';
  }
  out << "$EndElements\n";
  finish_writing(out, file);
}

void write_vtu(const std::filesystem::path& file, const TetMesh& mesh,
               const std::vector<CellField>& cell_fields) {
  for (const CellField& field : cell_fields) {
    if (field.values.size() != mesh.tets.rows()) {
      throw std::invalid_argument("cannot write '" + file.string() + "': cell field '" +
                                  field.name + "' has " + std::to_string(field.values.size()) +
                                  " values for " + std::to_string(mesh.tets.rows()) + " tets");
    }
  }
  std::ofstream out = open_for_writing(file);
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "<UnstructuredGrid>\n<Piece NumberOfPoints=\"" << mesh.vertices.rows()
      << "\" NumberOfCells=\"" << mesh.tets.rows() << "\">\n"
      << "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (Eigen::Index i = 0; i < mesh.vertices.rows(); ++i) {
    out << mesh.vertices(i, 0) << ' ' << mesh.vertices(i, 1) << ' ' << mesh.vertices(i, 2) << '\n';
  }
  out << "</DataArray>\n</Points>\n<Cells>\n"
      << "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (Eigen::Index i = 0; i < mesh.tets.rows(); ++i) {
    out << mesh.tets(i, 0) << ' ' << mesh.tets(i, 1) << ' ' << mesh.tets(i, 2) << ' '
        << mesh.tets(i, 3) << '\n';
  }
  out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  for (Eigen::Index i = 0; i < mesh.tets.rows(); ++i) out << 4 * (i + 1) << '\n';
  out << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (Eigen::Index i = 0; i < mesh.tets.rows(); ++i) out << "10\n";  // VTK_TETRA
  out << "</DataArray>\n</Cells>\n";
  if (!cell_fields.empty()) {
    out << "<CellData>\n";
    for (const CellField& field : cell_fields) {
      out << "<DataArray type=\"Float64\" Name=\"" << field.name << "\" format=\"ascii\">\n";
      for (Eigen::Index i = 0; i < field.values.size(); ++i) out << field.values[i] << '\n';
      out << "</DataArray>\n";
    }
    out << "</CellData>\n";
  }
  out << "</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  finish_writing(out, file);
}

}  // namespace grip::geometry
