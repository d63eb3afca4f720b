#include "src/geometry/repair.hpp"

#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/stitch_borders.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/alpha_wrap_3.h>

#include <Eigen/SVD>

#include <algorithm>
#include <array>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "src/geometry/cgal_surface_mesh.hpp"
#include "src/geometry/mesh_measures.hpp"

namespace grip::geometry {
namespace {

using Kernel = cgal::Kernel;
using Point = cgal::Point;
using CgalMesh = cgal::SurfaceMesh;
using Polygon = std::vector<std::size_t>;
namespace pmp = CGAL::Polygon_mesh_processing;

// A flat point set (all in one plane or line) bounds no volume. The thinnest extent is the
// smallest singular value of the centred points, scaled to a length.
bool is_flat(const Vertices& vertices) {
  const Eigen::RowVector3d centre = vertices.colwise().mean();
  const Eigen::MatrixXd centred = vertices.rowwise() - centre;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(centred);
  const Eigen::Vector3d sigma = svd.singularValues();
  return sigma[2] <= 1e-9 * sigma[0];
}

// Counts faces of `after` whose winding is the reverse of the same face in `before` (same
// face index, same corners). Orientation fixes in CGAL keep face indices.
int count_reversed(const std::vector<std::array<CgalMesh::Vertex_index, 3>>& before,
                   const CgalMesh& after) {
  int reversed = 0;
  for (std::size_t f = 0; f < before.size(); ++f) {
    const CgalMesh::Face_index face(static_cast<CgalMesh::size_type>(f));
    const auto h = after.halfedge(face);
    const auto a = after.source(h);
    const auto b = after.target(h);
    for (int k = 0; k < 3; ++k) {
      if (before[f][static_cast<std::size_t>(k)] == b &&
          before[f][static_cast<std::size_t>((k + 1) % 3)] == a) {
        ++reversed;
      }
    }
  }
  return reversed;
}

std::vector<std::array<CgalMesh::Vertex_index, 3>> face_corners(const CgalMesh& mesh) {
  std::vector<std::array<CgalMesh::Vertex_index, 3>> corners;
  for (const auto face : mesh.faces()) {
    const auto h = mesh.halfedge(face);
    corners.push_back({mesh.source(h), mesh.target(h), mesh.target(mesh.next(h))});
  }
  return corners;
}

}  // namespace

std::string RepairReport::summary() const {
  std::ostringstream out;
  out << "removed " << points_removed << " duplicate/unused points and " << faces_removed
      << " degenerate/duplicate faces, split " << points_split << " non-manifold points, stitched "
      << edges_stitched << " edges, filled " << holes_filled << " holes, reoriented "
      << faces_reoriented << " faces";
  if (self_intersecting) out << "; the surface intersected itself";
  out << (alpha_wrapped ? "; result: alpha-wrapped" : "; result: repaired input");
  return out.str();
}

RepairedSurface repair_surface(const SurfaceMesh& input, const RepairOptions& options,
                               const std::string& source) {
  if (input.vertices.rows() == 0 || input.triangles.rows() == 0) {
    throw std::invalid_argument("mesh " + source + " is empty: it has no triangles");
  }
  if (!input.vertices.allFinite()) {
    throw std::invalid_argument("mesh " + source + " has a NaN or infinite coordinate");
  }
  if (input.triangles.minCoeff() < 0 || input.triangles.maxCoeff() >= input.vertices.rows()) {
    throw std::invalid_argument("mesh " + source + " has a triangle index out of range");
  }
  if (is_flat(input.vertices)) {
    throw std::invalid_argument("mesh " + source +
                                " has zero volume: all its points lie in one plane; grip needs a "
                                "solid object");
  }
  RepairReport report;
  report.input_volume = surface_volume(input);

  std::vector<Point> points;
  for (Eigen::Index i = 0; i < input.vertices.rows(); ++i) {
    points.emplace_back(input.vertices(i, 0), input.vertices(i, 1), input.vertices(i, 2));
  }
  std::vector<Polygon> polygons;
  for (Eigen::Index f = 0; f < input.triangles.rows(); ++f) {
    polygons.push_back({static_cast<std::size_t>(input.triangles(f, 0)),
                        static_cast<std::size_t>(input.triangles(f, 1)),
                        static_cast<std::size_t>(input.triangles(f, 2))});
  }
  const std::size_t points_in = points.size();
  const std::size_t faces_in = polygons.size();
  pmp::repair_polygon_soup(points, polygons);
  report.points_removed = static_cast<int>(points_in - points.size());
  report.faces_removed = static_cast<int>(faces_in - polygons.size());
  if (polygons.empty()) {
    throw std::invalid_argument("mesh " + source +
                                " has no valid triangle left after removing degenerate ones");
  }
  // Wrapping an open surface starts from the cleaned soup, before any orientation change.
  const std::vector<Point> soup_points = points;
  const std::vector<Polygon> soup_polygons = polygons;

  const std::vector<Polygon> before_orient = polygons;
  const std::size_t points_before_orient = points.size();
  pmp::orient_polygon_soup(points, polygons);
  report.points_split = static_cast<int>(points.size() - points_before_orient);
  for (std::size_t f = 0; f < polygons.size(); ++f) {
    if (polygons[f] != before_orient[f]) {
      Polygon reversed(before_orient[f].rbegin(), before_orient[f].rend());
      if (std::is_permutation(reversed.begin(), reversed.end(), polygons[f].begin())) {
        ++report.faces_reoriented;
      }
    }
  }

  CgalMesh mesh;
  pmp::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  report.edges_stitched = static_cast<int>(pmp::stitch_borders(mesh));
  const std::size_t faces_before = mesh.number_of_faces();
  pmp::remove_degenerate_faces(mesh);
  mesh.collect_garbage();
  report.faces_removed += static_cast<int>(faces_before - mesh.number_of_faces());

  if (options.fill_holes && !CGAL::is_closed(mesh)) {
    std::vector<CgalMesh::Halfedge_index> cycles;
    pmp::extract_boundary_cycles(mesh, std::back_inserter(cycles));
    for (const auto h : cycles) {
      std::vector<CgalMesh::Face_index> patch;
      pmp::triangulate_hole(mesh, h, std::back_inserter(patch));
      if (!patch.empty()) ++report.holes_filled;
    }
  }

  const bool closed = CGAL::is_closed(mesh);
  report.self_intersecting = pmp::does_self_intersect(mesh);
  if (closed && !report.self_intersecting) {
    const auto corners = face_corners(mesh);
    pmp::orient_to_bound_a_volume(mesh);
    report.faces_reoriented += count_reversed(corners, mesh);
  } else {
    if (!options.allow_alpha_wrap) {
      throw std::invalid_argument(
          "mesh " + source + (closed ? " intersects itself" : " has open borders") +
          " and alpha wrapping is disabled; enable it or fix the mesh in a modeller");
    }
    const double diagonal = bounding_box_diagonal(input.vertices);
    const double alpha = options.alpha_ratio * diagonal;
    const double offset = options.offset_ratio * diagonal;
    CgalMesh wrapped;
    // A closed (hole-filled) surface seals its inside from the wrap, which then yields the
    // solid's outer hull; an open one is wrapped as the cleaned soup.
    if (closed) {
      CGAL::alpha_wrap_3(mesh, alpha, offset, wrapped);
    } else {
      CGAL::alpha_wrap_3(soup_points, soup_polygons, alpha, offset, wrapped);
    }
    pmp::orient_to_bound_a_volume(wrapped);
    report.alpha_wrapped = true;
    mesh = std::move(wrapped);
  }

  RepairedSurface result{cgal::from_cgal(mesh), report};
  result.report.volume = surface_volume(result.mesh);
  if (!(result.report.volume > 0.0)) {
    throw std::invalid_argument("mesh " + source +
                                " encloses no volume after repair; grip needs a solid object");
  }
  return result;
}

}  // namespace grip::geometry
