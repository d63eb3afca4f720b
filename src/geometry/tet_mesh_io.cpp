#include "src/geometry/tet_mesh_io.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "src/geometry/boundary_surface.hpp"
#include "src/geometry/mesh_measures.hpp"

namespace grip::geometry {
namespace {

using std::filesystem::path;

[[noreturn]] void refuse(const path& file, const std::string& problem) {
  throw std::runtime_error("cannot read tet mesh '" + file.string() + "': " + problem);
}

// The whitespace-separated words of a text file, with the checks every format needs: a word
// where one is due, numbers that parse, counts no larger than the file could hold.
class Words {
 public:
  explicit Words(const path& file) : file_(file), in_(file) {
    if (!in_) refuse(file, "the file cannot be opened");
    size_ = std::filesystem::file_size(file);
  }

  std::optional<std::string> next() {
    std::string word;
    while (in_ >> word) {
      if (!comment_ || word.front() != comment_) return word;
      std::string rest;
      std::getline(in_, rest);  // a comment runs to the end of its line
    }
    return std::nullopt;
  }
  std::string word(const std::string& what) {
    std::optional<std::string> w = next();
    if (!w) refuse(file_, "the file ends before " + what);
    return *w;
  }
  void expect(const std::string& keyword) {
    const std::string w = word(keyword);
    if (w != keyword) refuse(file_, "expected '" + keyword + "', found '" + w + "'");
  }
  long long integer(const std::string& what) {
    const std::string w = word(what);
    long long value = 0;
    const auto [end, error] = std::from_chars(w.data(), w.data() + w.size(), value);
    if (error != std::errc() || end != w.data() + w.size()) {
      refuse(file_, what + ": '" + w + "' is not an integer");
    }
    return value;
  }
  double number(const std::string& what) {
    const std::string w = word(what);
    try {
      std::size_t used = 0;
      const double value = std::stod(w, &used);
      if (used == w.size() && std::isfinite(value)) return value;
    } catch (const std::exception&) {
    }
    refuse(file_, what + ": '" + w + "' is not a finite number");
  }
  std::array<double, 3> point(const std::string& what) {
    const double x = number(what);
    const double y = number(what);
    return {x, y, number(what)};
  }
  // A count of entries of at least `bytes_each` bytes: not negative, and no more than the
  // file could hold (a damaged count must not size an allocation).
  std::size_t count(const std::string& what, std::size_t bytes_each) {
    const long long n = integer(what);
    if (n < 0 || static_cast<std::uintmax_t>(n) > size_ / bytes_each) {
      refuse(file_, what + " " + std::to_string(n) + " is more than the file holds");
    }
    return static_cast<std::size_t>(n);
  }
  // The rest of the current line, or nothing at the end of the file.
  std::optional<std::string> line() {
    std::string text;
    if (!std::getline(in_, text)) return std::nullopt;
    if (!text.empty() && text.back() == '\r') text.pop_back();
    return text;
  }
  void set_comment(char c) { comment_ = c; }
  const path& file() const { return file_; }

 private:
  path file_;
  std::ifstream in_;
  std::uintmax_t size_ = 0;
  char comment_ = 0;
};

// Points by their tag in the file (a Gmsh node tag, or a 0- or 1-based index) and tets by the
// tags of their corners, gathered into a mesh of the vertices the tets use, in file order.
struct TetSoup {
  std::vector<std::array<double, 3>> points;
  std::vector<long long> tags;  // tags[i] names points[i]
  std::vector<std::array<long long, 4>> tets;

  void add_point(long long tag, const std::array<double, 3>& point) {
    points.push_back(point);
    tags.push_back(tag);
  }

  // An element's `nodes` node tags; kept when it is a 4-node tet.
  void add_element(Words& words, long long type, std::size_t nodes, long long tet_type) {
    std::array<long long, 4> tet{};
    for (std::size_t k = 0; k < nodes; ++k) {
      const long long node = words.integer("an element's node");
      if (type == tet_type) tet[k] = node;
    }
    if (type == tet_type) tets.push_back(tet);
  }

  TetMesh mesh(const path& file) const {
    if (tets.empty()) refuse(file, "it holds no 4-node tetrahedron; export the volume mesh");
    std::unordered_map<long long, std::size_t> by_tag;
    for (std::size_t i = 0; i < tags.size(); ++i) {
      if (!by_tag.emplace(tags[i], i).second) {
        refuse(file, "vertex " + std::to_string(tags[i]) + " is defined twice");
      }
    }
    std::vector<int> renumbered(points.size(), -1);
    for (const auto& tet : tets) {
      for (const long long tag : tet) {
        const auto it = by_tag.find(tag);
        if (it == by_tag.end()) {
          refuse(file, "a tetrahedron refers to vertex " + std::to_string(tag) +
                           ", which the file does not define");
        }
        renumbered[it->second] = 0;
      }
    }
    TetMesh mesh;
    int used = 0;
    for (int& index : renumbered) {
      if (index == 0) index = used++;
    }
    mesh.vertices.resize(used, 3);
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (renumbered[i] < 0) continue;
      for (int c = 0; c < 3; ++c) mesh.vertices(renumbered[i], c) = points[i][std::size_t(c)];
    }
    mesh.tets.resize(static_cast<Eigen::Index>(tets.size()), 4);
    for (std::size_t t = 0; t < tets.size(); ++t) {
      for (int c = 0; c < 4; ++c) {
        mesh.tets(static_cast<Eigen::Index>(t), c) =
            renumbered[by_tag.at(tets[t][static_cast<std::size_t>(c)])];
      }
    }
    return mesh;
  }
};

// ---- legacy VTK ------------------------------------------------------------------------------

constexpr int kVtkTetra = 10;

TetMesh read_vtk(const path& file) {
  Words words(file);
  const std::string header = words.line().value_or("");
  if (header.rfind("# vtk DataFile Version", 0) != 0) {
    refuse(file,
           "not a legacy VTK file (its first line is not '# vtk DataFile Version ...'); "
           "VTK XML (.vtu) is not read, save it as legacy .vtk");
  }
  const bool offsets_layout = header.find("Version 5") != std::string::npos;
  words.line();  // the title
  const std::string encoding = words.word("the encoding");
  if (encoding != "ASCII") refuse(file, "it is " + encoding + "; save it as ASCII");
  words.expect("DATASET");
  const std::string type = words.word("the dataset type");
  if (type != "UNSTRUCTURED_GRID") {
    refuse(file, "its dataset is " + type + ", not an UNSTRUCTURED_GRID of tetrahedra");
  }
  TetSoup soup;
  std::vector<std::vector<long long>> cells;
  std::vector<long long> cell_types;
  bool have_points = false;
  while (std::optional<std::string> section = words.next()) {
    if (*section == "POINTS") {
      const std::size_t n = words.count("POINTS", 6);
      words.word("the POINTS data type");
      for (std::size_t i = 0; i < n; ++i) {
        soup.add_point(static_cast<long long>(i), words.point("a point"));
      }
      have_points = true;
    } else if (*section == "CELLS" && offsets_layout) {
      const std::size_t offsets = words.count("CELLS offsets", 2);
      const std::size_t connectivity = words.count("CELLS connectivity", 2);
      words.expect("OFFSETS");
      words.word("the OFFSETS data type");
      std::vector<long long> offset(offsets);
      for (auto& o : offset) o = words.integer("an offset");
      words.expect("CONNECTIVITY");
      words.word("the CONNECTIVITY data type");
      std::vector<long long> ids(connectivity);
      for (auto& id : ids) id = words.integer("a cell's point");
      for (std::size_t c = 0; c + 1 < offsets; ++c) {
        if (offset[c] < 0 || offset[c] > offset[c + 1] ||
            offset[c + 1] > static_cast<long long>(connectivity)) {
          refuse(file, "the CELLS offsets are not increasing within the connectivity");
        }
        cells.emplace_back(ids.begin() + offset[c], ids.begin() + offset[c + 1]);
      }
    } else if (*section == "CELLS") {
      const std::size_t n = words.count("CELLS", 4);
      words.count("the CELLS size", 2);
      for (std::size_t c = 0; c < n; ++c) {
        const std::size_t k = words.count("a cell's point count", 2);
        std::vector<long long>& cell = cells.emplace_back(k);
        for (auto& id : cell) id = words.integer("a cell's point");
      }
    } else if (*section == "CELL_TYPES") {
      const std::size_t n = words.count("CELL_TYPES", 2);
      cell_types.resize(n);
      for (auto& t : cell_types) t = words.integer("a cell type");
    } else if (*section == "METADATA") {
      words.line();  // the keyword's own line; the block ends at a blank line
      for (std::optional<std::string> l = words.line(); l && !l->empty(); l = words.line()) {
      }
    } else if (*section == "POINT_DATA" || *section == "CELL_DATA") {
      break;  // fields follow; a finger needs none
    } else {
      refuse(file, "unknown section '" + *section + "'");
    }
  }
  if (!have_points) refuse(file, "it has no POINTS section");
  if (cell_types.size() != cells.size()) {
    refuse(file, "it has " + std::to_string(cells.size()) + " CELLS but " +
                     std::to_string(cell_types.size()) + " CELL_TYPES");
  }
  for (std::size_t c = 0; c < cells.size(); ++c) {
    if (cell_types[c] != kVtkTetra) continue;
    if (cells[c].size() != 4)
      refuse(file, "a VTK_TETRA cell has " + std::to_string(cells[c].size()) + " points");
    soup.tets.push_back({cells[c][0], cells[c][1], cells[c][2], cells[c][3]});
  }
  return soup.mesh(file);
}

// ---- Gmsh ------------------------------------------------------------------------------------

constexpr long long kGmshTet = 4;
constexpr long long kGmshTet10 = 11;

// Nodes of each Gmsh element type a mesh may carry beside its tets.
std::optional<std::size_t> gmsh_nodes(long long type) {
  static const std::map<long long, std::size_t> nodes = {
      {1, 2},  {2, 3},  {3, 4},   {4, 4},   {5, 8},   {6, 6},   {7, 5},
      {8, 3},  {9, 6},  {10, 9},  {11, 10}, {12, 27}, {13, 18}, {14, 14},
      {15, 1}, {16, 8}, {17, 20}, {18, 15}, {19, 13}};
  const auto it = nodes.find(type);
  if (it == nodes.end()) return std::nullopt;
  return it->second;
}

std::size_t element_nodes(Words& words, long long type) {
  if (type == kGmshTet10) {
    refuse(words.file(),
           "it has second-order (10-node) tetrahedra; export a first-order mesh "
           "(gmsh -3 -order 1)");
  }
  const std::optional<std::size_t> n = gmsh_nodes(type);
  if (!n) refuse(words.file(), "unknown element type " + std::to_string(type));
  return *n;
}

void read_gmsh2_nodes(Words& words, TetSoup& soup) {
  const std::size_t n = words.count("$Nodes count", 8);
  for (std::size_t i = 0; i < n; ++i) {
    const long long tag = words.integer("a node tag");
    soup.add_point(tag, words.point("a node"));
  }
}

void read_gmsh2_elements(Words& words, TetSoup& soup) {
  const std::size_t n = words.count("$Elements count", 8);
  for (std::size_t e = 0; e < n; ++e) {
    words.integer("an element tag");
    const long long type = words.integer("an element type");
    const std::size_t tags = words.count("an element's tag count", 2);
    for (std::size_t t = 0; t < tags; ++t) words.integer("an element tag");
    soup.add_element(words, type, element_nodes(words, type), kGmshTet);
  }
}

// A Gmsh 4.1 section opens with its block count, entry count and smallest and largest tags;
// each block with its dimension, entity, a third number (nodes: whether parametric;
// elements: the type) and its size.
std::size_t gmsh4_blocks(Words& words, const std::string& section) {
  const std::size_t blocks = words.count(section + " block count", 8);
  words.count(section + " count", 4);
  words.integer(section + "'s smallest tag");
  words.integer(section + "'s largest tag");
  return blocks;
}

struct Gmsh4Block {
  long long dimension = 0;
  long long third = 0;
  std::size_t size = 0;
};

Gmsh4Block gmsh4_block(Words& words, const std::string& section) {
  Gmsh4Block block;
  block.dimension = words.integer(section + " block's dimension");
  words.integer(section + " block's entity");
  block.third = words.integer(section + " block's " +
                              (section == "$Nodes" ? "parametric flag" : "element type"));
  block.size = words.count(section + " block's size", 4);
  return block;
}

void read_gmsh4_nodes(Words& words, TetSoup& soup) {
  for (std::size_t b = gmsh4_blocks(words, "$Nodes"); b > 0; --b) {
    const Gmsh4Block block = gmsh4_block(words, "$Nodes");
    std::vector<long long> tags(block.size);
    for (auto& tag : tags) tag = words.integer("a node tag");
    for (const long long tag : tags) {
      const std::array<double, 3> point = words.point("a node");
      for (long long u = 0; block.third != 0 && u < block.dimension; ++u) {
        words.number("a node's parameter");
      }
      soup.add_point(tag, point);
    }
  }
}

void read_gmsh4_elements(Words& words, TetSoup& soup) {
  for (std::size_t b = gmsh4_blocks(words, "$Elements"); b > 0; --b) {
    const Gmsh4Block block = gmsh4_block(words, "$Elements");
    const std::size_t nodes = element_nodes(words, block.third);
    for (std::size_t e = 0; e < block.size; ++e) {
      words.integer("an element tag");
      soup.add_element(words, block.third, nodes, kGmshTet);
    }
  }
}

TetMesh read_msh(const path& file) {
  Words words(file);
  words.expect("$MeshFormat");
  const std::string version = words.word("the format version");
  const long long file_type = words.integer("the file type");
  words.word("the data size");
  if (file_type != 0) refuse(file, "it is binary; save it as ASCII (gmsh -save -bin 0)");
  const bool v2 = version.rfind("2.", 0) == 0;
  if (!v2 && version != "4.1") {
    refuse(file, "Gmsh format " + version +
                     " is not read; save as 4.1 or 2.2 "
                     "(gmsh -format msh41 or msh22)");
  }
  words.expect("$EndMeshFormat");
  TetSoup soup;
  while (std::optional<std::string> section = words.next()) {
    if (section->empty() || section->front() != '$') {
      refuse(file, "expected a section ($Name), found '" + *section + "'");
    }
    const std::string name = section->substr(1);
    if (name == "Nodes") {
      v2 ? read_gmsh2_nodes(words, soup) : read_gmsh4_nodes(words, soup);
    } else if (name == "Elements") {
      v2 ? read_gmsh2_elements(words, soup) : read_gmsh4_elements(words, soup);
    } else {
      // Physical names, entities, periodic links, data: not needed for the tets.
      while (words.word("$End" + name) != "$End" + name) {
      }
      continue;
    }
    words.expect("$End" + name);
  }
  return soup.mesh(file);
}

// ---- MEDIT -----------------------------------------------------------------------------------

TetMesh read_medit(const path& file) {
  Words words(file);
  words.set_comment('#');
  // Words per entry of the sections a volume mesh may carry beside its vertices and tets.
  static const std::map<std::string, std::size_t> skipped = {{"Edges", 3},
                                                             {"Triangles", 4},
                                                             {"Quadrilaterals", 5},
                                                             {"Hexahedra", 9},
                                                             {"Prisms", 7},
                                                             {"Corners", 1},
                                                             {"RequiredVertices", 1},
                                                             {"Ridges", 1},
                                                             {"RequiredEdges", 1},
                                                             {"RequiredTriangles", 1},
                                                             {"Normals", 3},
                                                             {"NormalAtVertices", 2},
                                                             {"Tangents", 3},
                                                             {"TangentAtVertices", 2}};
  TetSoup soup;
  words.expect("MeshVersionFormatted");
  words.integer("the format version");
  while (std::optional<std::string> keyword = words.next()) {
    if (*keyword == "End") break;
    if (*keyword == "Dimension") {
      const long long dimension = words.integer("the dimension");
      if (dimension != 3) refuse(file, "it is a " + std::to_string(dimension) + "D mesh");
    } else if (*keyword == "Vertices") {
      const std::size_t n = words.count("Vertices", 8);
      for (std::size_t i = 0; i < n; ++i) {
        const std::array<double, 3> point = words.point("a vertex");
        words.integer("a vertex's reference");
        soup.add_point(static_cast<long long>(i + 1), point);  // MEDIT counts from 1
      }
    } else if (*keyword == "Tetrahedra") {
      const std::size_t n = words.count("Tetrahedra", 10);
      for (std::size_t t = 0; t < n; ++t) {
        std::array<long long, 4> tet{};
        for (auto& v : tet) v = words.integer("a tetrahedron's vertex");
        words.integer("a tetrahedron's reference");
        soup.tets.push_back(tet);
      }
    } else if (const auto it = skipped.find(*keyword); it != skipped.end()) {
      const std::size_t n = words.count(*keyword, 2 * it->second);
      for (std::size_t k = 0; k < n * it->second; ++k) words.word(*keyword);
    } else {
      refuse(file, "unknown MEDIT keyword '" + *keyword + "'");
    }
  }
  return soup.mesh(file);
}

std::string lower_extension(const path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace

bool is_tet_mesh_file(const path& file) {
  const std::string ext = lower_extension(file);
  return ext == ".vtk" || ext == ".msh" || ext == ".mesh";
}

TetMesh read_tet_mesh(const path& file) {
  const std::string ext = lower_extension(file);
  if (!is_tet_mesh_file(file)) {
    refuse(file, "unknown tet mesh format '" + ext +
                     "'; use .vtk (legacy VTK), .msh (Gmsh) or "
                     ".mesh (MEDIT)");
  }
  if (!std::filesystem::is_regular_file(file)) refuse(file, "no such file");
  if (ext == ".vtk") return read_vtk(file);
  if (ext == ".msh") return read_msh(file);
  return read_medit(file);
}

void check_soft_body_mesh(TetMesh& mesh, const std::string& source, double max_size_m) {
  const auto fail = [&](const std::string& problem) {
    throw std::runtime_error(source + ": " + problem);
  };
  const double size = bounding_box_diagonal(mesh.vertices);
  if (size > max_size_m) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "the mesh is %.4g m across, larger than %.4g m: are its units millimetres? "
                  "Scale it to metres",
                  size, max_size_m);
    fail(text);
  }
  const auto volume = [&](Eigen::Index t) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.tets(t, 0));
    return (Eigen::Vector3d(mesh.vertices.row(mesh.tets(t, 1))) - a)
               .cross(Eigen::Vector3d(mesh.vertices.row(mesh.tets(t, 2))) - a)
               .dot(Eigen::Vector3d(mesh.vertices.row(mesh.tets(t, 3))) - a) /
           6.0;
  };
  // Degenerate: a tet whose volume is a millionth of a regular tet on its longest edge.
  Eigen::Index positive = 0;
  Eigen::Index negative = 0;
  for (Eigen::Index t = 0; t < mesh.tets.rows(); ++t) {
    double longest = 0.0;
    for (int i = 0; i < 4; ++i) {
      for (int j = i + 1; j < 4; ++j) {
        longest = std::max(
            longest,
            (mesh.vertices.row(mesh.tets(t, i)) - mesh.vertices.row(mesh.tets(t, j))).norm());
      }
    }
    const double v = volume(t);
    if (!(std::abs(v) > 1e-6 * longest * longest * longest / (6.0 * std::sqrt(2.0)))) {
      fail("tet " + std::to_string(t) +
           " is degenerate (its four vertices nearly coplanar or "
           "repeated); remesh the body");
    }
    (v > 0 ? positive : negative) += 1;
  }
  if (positive > 0 && negative > 0) {
    fail(std::to_string(std::min(positive, negative)) + " of " + std::to_string(mesh.tets.rows()) +
         " tets are inverted (oriented against the rest); "
         "remesh the body or fix their vertex order");
  }
  if (negative > 0) mesh.tets.col(1).swap(mesh.tets.col(2));
  // The boundary is a closed manifold when no face joins more than two tets, every boundary
  // edge joins exactly two boundary faces and the faces around each boundary vertex make one
  // fan (tets that meet at a vertex only make two).
  std::map<std::array<int, 3>, int> face_tets;
  for (Eigen::Index t = 0; t < mesh.tets.rows(); ++t) {
    for (int skip = 0; skip < 4; ++skip) {
      std::array<int, 3> face{};
      for (int c = 0, k = 0; c < 4; ++c) {
        if (c != skip) face[static_cast<std::size_t>(k++)] = mesh.tets(t, c);
      }
      std::sort(face.begin(), face.end());
      if (++face_tets[face] > 2) fail("a face is shared by three tets or more; remesh the body");
    }
  }
  const SurfaceMesh boundary = boundary_surface(mesh);
  std::map<std::pair<int, int>, int> edge_faces;
  std::vector<std::vector<std::pair<int, int>>> link(
      static_cast<std::size_t>(boundary.vertices.rows()));
  for (Eigen::Index f = 0; f < boundary.triangles.rows(); ++f) {
    for (int c = 0; c < 3; ++c) {
      const int a = boundary.triangles(f, c);
      const int b = boundary.triangles(f, (c + 1) % 3);
      const int opposite = boundary.triangles(f, (c + 2) % 3);
      ++edge_faces[{std::min(a, b), std::max(a, b)}];
      link[static_cast<std::size_t>(opposite)].emplace_back(a, b);
    }
  }
  for (const auto& [edge, faces] : edge_faces) {
    if (faces != 2) {
      fail("the boundary is not a closed manifold (an edge lies on " + std::to_string(faces) +
           " boundary faces); remesh the body");
    }
  }
  const std::string pinched =
      "the boundary is not a closed manifold (tets meet at a vertex only); remesh the body";
  for (const auto& edges : link) {
    // Each link edge (a, b) leads from a to b; one fan is one cycle through all of them.
    std::map<int, int> next;
    for (const auto& [a, b] : edges) {
      if (!next.emplace(a, b).second) fail(pinched);
    }
    std::size_t steps = 1;
    for (int at = edges.front().second; at != edges.front().first; ++steps) {
      const auto it = next.find(at);
      if (it == next.end() || steps > edges.size()) fail(pinched);
      at = it->second;
    }
    if (steps != edges.size()) fail(pinched);
  }
}

}  // namespace grip::geometry
