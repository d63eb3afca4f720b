#pragma once
// Conversions between grip's SurfaceMesh and CGAL's Surface_mesh, for the geometry .cpp files
// that already include CGAL (include it in no header: CGAL costs seconds per translation unit).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/polygon_mesh_to_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <array>
#include <optional>
#include <vector>

#include "src/geometry/mesh.hpp"

namespace grip::geometry::cgal {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;

// The surface as a CGAL mesh; empty when its triangles do not form a manifold polygon mesh
// (each caller says what that means for its input).
inline std::optional<SurfaceMesh> to_cgal(const geometry::SurfaceMesh& surface) {
  std::vector<Point> points;
  points.reserve(static_cast<std::size_t>(surface.vertices.rows()));
  for (Eigen::Index i = 0; i < surface.vertices.rows(); ++i) {
    points.emplace_back(surface.vertices(i, 0), surface.vertices(i, 1), surface.vertices(i, 2));
  }
  std::vector<std::array<std::size_t, 3>> faces;
  faces.reserve(static_cast<std::size_t>(surface.triangles.rows()));
  for (Eigen::Index f = 0; f < surface.triangles.rows(); ++f) {
    faces.push_back({static_cast<std::size_t>(surface.triangles(f, 0)),
                     static_cast<std::size_t>(surface.triangles(f, 1)),
                     static_cast<std::size_t>(surface.triangles(f, 2))});
  }
  if (!CGAL::Polygon_mesh_processing::is_polygon_soup_a_polygon_mesh(faces)) return std::nullopt;
  SurfaceMesh mesh;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, faces, mesh);
  return mesh;
}

// A triangle mesh of CGAL's as a SurfaceMesh (vertices renumbered densely).
inline geometry::SurfaceMesh from_cgal(const SurfaceMesh& mesh) {
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  CGAL::Polygon_mesh_processing::polygon_mesh_to_polygon_soup(mesh, points, polygons);
  geometry::SurfaceMesh result;
  result.vertices.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) {
    result.vertices.row(static_cast<Eigen::Index>(i)) << points[i].x(), points[i].y(),
        points[i].z();
  }
  result.triangles.resize(static_cast<Eigen::Index>(polygons.size()), 3);
  for (std::size_t f = 0; f < polygons.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      result.triangles(static_cast<Eigen::Index>(f), k) =
          static_cast<int>(polygons[f][static_cast<std::size_t>(k)]);
    }
  }
  return result;
}

}  // namespace grip::geometry::cgal
