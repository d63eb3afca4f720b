#include "src/geometry/boolean_union.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/polygon_mesh_to_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Surface_mesh.h>

#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace grip::geometry {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using CgalMesh = CGAL::Surface_mesh<Point>;
namespace pmp = CGAL::Polygon_mesh_processing;

CgalMesh to_cgal_mesh(const SurfaceMesh& surface, const std::string& what) {
  std::vector<Point> points;
  for (Eigen::Index i = 0; i < surface.vertices.rows(); ++i) {
    points.emplace_back(surface.vertices(i, 0), surface.vertices(i, 1), surface.vertices(i, 2));
  }
  std::vector<std::array<std::size_t, 3>> faces;
  for (Eigen::Index f = 0; f < surface.triangles.rows(); ++f) {
    faces.push_back({static_cast<std::size_t>(surface.triangles(f, 0)),
                     static_cast<std::size_t>(surface.triangles(f, 1)),
                     static_cast<std::size_t>(surface.triangles(f, 2))});
  }
  if (!pmp::is_polygon_soup_a_polygon_mesh(faces)) {
    throw std::invalid_argument(what + ": an operand is not a manifold surface");
  }
  CgalMesh mesh;
  pmp::polygon_soup_to_polygon_mesh(points, faces, mesh);
  if (!CGAL::is_closed(mesh)) throw std::invalid_argument(what + ": an operand is not closed");
  return mesh;
}

}  // namespace

SurfaceMesh boolean_union(const SurfaceMesh& a, const SurfaceMesh& b, const std::string& what) {
  CgalMesh first = to_cgal_mesh(a, what);
  CgalMesh second = to_cgal_mesh(b, what);
  CgalMesh result;
  if (!pmp::corefine_and_compute_union(first, second, result)) {
    throw std::invalid_argument(what + ": the union is not a valid solid (an operand "
                                       "intersects itself or is not outward oriented)");
  }
  // Corefinement leaves slivers of triangles along the intersection curve (edges down to
  // 1e-18 m, angles near 0 or 180 degrees), on which tetrahedralization degenerates. Needles
  // whose short edge is under 0.2 mm are collapsed and caps flipped; nothing an object's
  // shape depends on is that small.
  pmp::experimental::remove_almost_degenerate_faces(faces(result), result,
                                                    /*cap_threshold=*/std::cos(160.0 * CGAL_PI / 180.0),
                                                    /*needle_threshold=*/100.0,
                                                    /*collapse_length_threshold=*/2e-4);
  result.collect_garbage();
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  pmp::polygon_mesh_to_polygon_soup(result, points, polygons);
  SurfaceMesh out;
  out.vertices.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) {
    out.vertices.row(static_cast<Eigen::Index>(i)) << points[i].x(), points[i].y(), points[i].z();
  }
  out.triangles.resize(static_cast<Eigen::Index>(polygons.size()), 3);
  for (std::size_t f = 0; f < polygons.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      out.triangles(static_cast<Eigen::Index>(f), k) =
          static_cast<int>(polygons[f][static_cast<std::size_t>(k)]);
    }
  }
  return out;
}

}  // namespace grip::geometry
