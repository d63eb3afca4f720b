#include "src/geometry/tetrahedralize.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polyhedral_mesh_domain_with_features_3.h>
#include <CGAL/Random.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/exude_mesh_3.h>
#include <CGAL/make_mesh_3.h>
#include <CGAL/perturb_mesh_3.h>
#include <spdlog/spdlog.h>

#include <array>
#include <stdexcept>
#include <unordered_map>
#include <vector>

#include "src/geometry/mesh_measures.hpp"

namespace grip::geometry {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using CgalMesh = CGAL::Surface_mesh<Point>;
using Domain = CGAL::Polyhedral_mesh_domain_with_features_3<Kernel, CgalMesh>;
using Triangulation = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using Complex = CGAL::Mesh_complex_3_in_triangulation_3<Triangulation, Domain::Corner_index,
                                                        Domain::Curve_index>;
using Criteria = CGAL::Mesh_criteria_3<Triangulation>;
namespace pmp = CGAL::Polygon_mesh_processing;

CgalMesh to_cgal_mesh(const SurfaceMesh& surface, const std::string& source) {
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
  if (!pmp::is_polygon_soup_a_polygon_mesh(faces)) {
    throw std::invalid_argument("cannot tetrahedralize " + source +
                                ": the surface is not manifold; repair it first "
                                "(geometry::repair_surface or `grip asset prepare`)");
  }
  CgalMesh mesh;
  pmp::polygon_soup_to_polygon_mesh(points, faces, mesh);
  return mesh;
}

}  // namespace

TetMesh tetrahedralize(const SurfaceMesh& closed_surface, const TetOptions& options,
                       const std::string& source) {
  if (!(options.edge_length > 0.0)) {
    throw std::invalid_argument("cannot tetrahedralize " + source +
                                ": the target edge length must be positive");
  }
  const CgalMesh mesh = to_cgal_mesh(closed_surface, source);
  if (!CGAL::is_closed(mesh)) {
    throw std::invalid_argument("cannot tetrahedralize " + source +
                                ": the surface has open borders; repair it first "
                                "(geometry::repair_surface or `grip asset prepare`)");
  }
  if (pmp::does_self_intersect(mesh)) {
    throw std::invalid_argument("cannot tetrahedralize " + source +
                                ": the surface intersects itself; repair it first "
                                "(geometry::repair_surface or `grip asset prepare`)");
  }
  if (!(surface_volume(closed_surface) > 0.0)) {
    throw std::invalid_argument("cannot tetrahedralize " + source +
                                ": the surface encloses no positive volume (flat, or facing "
                                "inward); repair it first");
  }

  CGAL::Random random(options.seed);
  Domain domain(mesh, &random);
  domain.detect_features(options.feature_angle_deg);
  const double h = options.edge_length;
  namespace params = CGAL::parameters;
  const Criteria criteria(params::edge_size = h, params::facet_angle = options.facet_angle_deg,
                          params::facet_size = h,
                          params::facet_distance = options.facet_distance_ratio * h,
                          params::cell_radius_edge_ratio = options.cell_radius_edge_ratio,
                          params::cell_size = h);
  Complex complex = CGAL::make_mesh_3<Complex>(domain, criteria, params::no_odt(),
                                               params::no_lloyd(), params::no_perturb(),
                                               params::no_exude());
  if (options.perturb_time_limit_s > 0.0) {
    const CGAL::Mesh_optimization_return_code code =
        CGAL::perturb_mesh_3(complex, domain, params::sliver_bound = options.sliver_bound_deg,
                             params::time_limit = options.perturb_time_limit_s);
    if (code == CGAL::TIME_LIMIT_REACHED) {
      spdlog::warn("tetrahedralizing {}: sliver perturbation stopped at its {} s limit, so this "
                   "mesh may differ on a faster or slower machine; keep the written mesh",
                   source, options.perturb_time_limit_s);
    }
  }
  // Exudation only changes weights and always terminates: no time limit, deterministic.
  CGAL::exude_mesh_3(complex, params::sliver_bound = options.sliver_bound_deg,
                     params::time_limit = 0);

  std::unordered_map<Triangulation::Vertex_handle, int> index;
  std::vector<Point> points;
  std::vector<std::array<int, 4>> tets;
  for (auto cell = complex.cells_in_complex_begin(); cell != complex.cells_in_complex_end();
       ++cell) {
    std::array<int, 4> tet{};
    for (int k = 0; k < 4; ++k) {
      const auto vertex = cell->vertex(k);
      auto [it, inserted] = index.try_emplace(vertex, static_cast<int>(points.size()));
      if (inserted) points.push_back(vertex->point().point());
      tet[static_cast<std::size_t>(k)] = it->second;
    }
    tets.push_back(tet);
  }
  if (tets.empty()) {
    throw std::runtime_error("tetrahedralizing " + source +
                             " produced no tets: the edge length " + std::to_string(h) +
                             " m is too large for the object; use a smaller one");
  }
  TetMesh result;
  result.vertices.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) {
    result.vertices.row(static_cast<Eigen::Index>(i)) << points[i].x(), points[i].y(),
        points[i].z();
  }
  result.tets.resize(static_cast<Eigen::Index>(tets.size()), 4);
  for (std::size_t t = 0; t < tets.size(); ++t) {
    const auto row = static_cast<Eigen::Index>(t);
    result.tets.row(row) << tets[t][0], tets[t][1], tets[t][2], tets[t][3];
    // CGAL cells are positively oriented in CGAL's sense; check with our formula anyway so a
    // convention mismatch can never leak out.
    const Eigen::Vector3d x0 = result.vertices.row(tets[t][0]);
    const Eigen::Vector3d x1 = result.vertices.row(tets[t][1]);
    const Eigen::Vector3d x2 = result.vertices.row(tets[t][2]);
    const Eigen::Vector3d x3 = result.vertices.row(tets[t][3]);
    if ((x1 - x0).cross(x2 - x0).dot(x3 - x0) < 0.0) std::swap(result.tets(row, 2), result.tets(row, 3));
  }
  return result;
}

}  // namespace grip::geometry
