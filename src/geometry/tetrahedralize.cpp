#include "src/geometry/tetrahedralize.hpp"

#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polyhedral_mesh_domain_with_features_3.h>
#include <CGAL/exude_mesh_3.h>
#include <CGAL/make_mesh_3.h>
#include <CGAL/perturb_mesh_3.h>
#include <CGAL/refine_mesh_3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
#include <unordered_map>
#include <vector>

#include "src/geometry/cgal_surface_mesh.hpp"
#include "src/geometry/mesh_measures.hpp"
#include "src/geometry/signed_distance.hpp"

namespace grip::geometry {
namespace {

using Kernel = cgal::Kernel;
using Point = cgal::Point;
using CgalMesh = cgal::SurfaceMesh;
using Domain = CGAL::Polyhedral_mesh_domain_with_features_3<Kernel, CgalMesh>;
using Triangulation = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using Complex = CGAL::Mesh_complex_3_in_triangulation_3<Triangulation, Domain::Corner_index,
                                                        Domain::Curve_index>;
using Criteria = CGAL::Mesh_criteria_3<Triangulation>;
namespace pmp = CGAL::Polygon_mesh_processing;
namespace params = CGAL::parameters;

// Surface points that seed the Delaunay refinement where protected features alone do not (a
// smooth shape has no features). Mesh_3's own seeds come from rays shot from the bounding-box
// centre; for a torus that centre lies in the hole and every seed lands on the inner rim, and
// the refinement then finds no surface at all. Farthest-point sampling over the face centroids
// spreads the seeds over every part of the surface instead, starting from face `seed` modulo
// the face count.
constexpr int kSeedPoints = 24;

std::vector<std::pair<Point, Domain::Index>> spread_surface_points(const SurfaceMesh& surface,
                                                                   const Domain& domain,
                                                                   double edge_length,
                                                                   std::uint32_t seed) {
  const Eigen::Index faces = surface.triangles.rows();
  Eigen::MatrixX3d centroids(faces, 3);
  Eigen::MatrixX3d normals(faces, 3);
  for (Eigen::Index f = 0; f < faces; ++f) {
    const Eigen::Vector3d a = surface.vertices.row(surface.triangles(f, 0));
    const Eigen::Vector3d b = surface.vertices.row(surface.triangles(f, 1));
    const Eigen::Vector3d c = surface.vertices.row(surface.triangles(f, 2));
    centroids.row(f) = (a + b + c) / 3.0;
    normals.row(f) = (b - a).cross(c - a).normalized();
  }
  std::vector<double> distance(static_cast<std::size_t>(faces),
                               std::numeric_limits<double>::infinity());
  const auto intersection = domain.construct_intersection_object();
  std::vector<std::pair<Point, Domain::Index>> seeds;
  Eigen::Index next = static_cast<Eigen::Index>(seed % static_cast<std::uint64_t>(faces));
  for (int k = 0; k < std::min<Eigen::Index>(kSeedPoints, faces); ++k) {
    // A short segment through the centroid along the normal meets the surface at (or next to)
    // the face; the domain's intersection supplies the surface patch index with the point.
    const Eigen::Index current = next;
    const Eigen::Vector3d c = centroids.row(current);
    const Eigen::Vector3d d = 0.1 * edge_length * normals.row(current);
    const auto hit =
        intersection(Kernel::Segment_3(Point(c.x() + d.x(), c.y() + d.y(), c.z() + d.z()),
                                       Point(c.x() - d.x(), c.y() - d.y(), c.z() - d.z())));
    if (std::get<2>(hit) != 0) seeds.emplace_back(std::get<0>(hit), std::get<1>(hit));
    double farthest = -1.0;
    for (Eigen::Index f = 0; f < faces; ++f) {
      auto& nearest = distance[static_cast<std::size_t>(f)];
      nearest = std::min(nearest, (centroids.row(f) - centroids.row(current)).squaredNorm());
      if (nearest > farthest) {
        farthest = nearest;
        next = f;
      }
    }
  }
  return seeds;
}

// The largest circumradius a cell may have, where Mesh_3 asks (at its circumcentre): the edge
// length down to a depth of one edge length, then growing by `growth` per metre of depth, up
// to `largest`. A cell with a vertex on the surface has its circumcentre no deeper than its
// circumradius r, so it is good only if r <= edge_length + growth (r - edge_length): for a
// growth below 1 that forces r <= edge_length, the uniform mesh's bound. At 1 and above it is
// not forced, only measured: the largest such r on a 12 x 10 x 9 cm box at 8 mm is 1.14
// edge lengths at growth 1 and 2, as in the uniform mesh (test
// AGradedMeshKeepsTheSurfaceTetsAndCoarsensTheInside).
struct GradedCellSize {
  const SignedDistance* depth;  // positive inside
  double edge_length;
  double growth;
  double largest;
  double operator()(const Point& p, int, const Domain::Index&) const {
    const double below = (*depth)(Eigen::Vector3d(p.x(), p.y(), p.z())) - edge_length;
    return std::min(largest, edge_length + growth * std::max(0.0, below));
  }
};

// Mesh_3's initialization (as make_mesh_3 does it) with two changes: protecting balls on
// sharp features never shrink below `minimal_ball_radius` (without that floor, the
// near-zero-length seam edges of a sampled mug kept the protection running for minutes), and
// smooth surfaces are seeded by spread_surface_points.
Complex initial_complex(const SurfaceMesh& surface, const Domain& domain, const Criteria& criteria,
                        const TetOptions& options) {
  Complex complex;
  using Sizing =
      CGAL::Mesh_3::internal::Edge_criteria_sizing_field_wrapper<Criteria::Edge_criteria>;
  CGAL::Mesh_3::Protect_edges_sizing_field<Complex, Domain, Sizing> protect(
      complex, domain, Sizing(criteria.edge_criteria_object()),
      options.minimal_ball_ratio * options.edge_length);
  protect(true);
  bool seeded = complex.triangulation().dimension() == 3;
  if (seeded) {
    CGAL::Mesh_3::C3T3_helpers<Complex, Domain> helper(complex, domain);
    helper.update_restricted_facets();
    seeded = complex.number_of_facets() > 0;
  }
  if (!seeded) {
    const auto weighted = complex.triangulation().geom_traits().construct_weighted_point_3_object();
    for (const auto& [point, index] :
         spread_surface_points(surface, domain, options.edge_length, options.seed)) {
      const auto vertex = complex.triangulation().insert(weighted(point));
      if (vertex == Triangulation::Vertex_handle()) continue;  // hidden by a protecting ball
      complex.set_dimension(vertex, 2);
      complex.set_index(vertex, index);
    }
  }
  return complex;
}

// The smallest of a tet's six dihedral angles, in degrees.
double min_dihedral_deg(const Triangulation::Cell_handle& cell) {
  constexpr int kEdges[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2},
                                {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}};
  double smallest = 180.0;
  for (const auto& e : kEdges) {
    smallest = std::min(
        smallest, std::abs(CGAL::approximate_dihedral_angle(
                      cell->vertex(e[0])->point().point(), cell->vertex(e[1])->point().point(),
                      cell->vertex(e[2])->point().point(), cell->vertex(e[3])->point().point())));
  }
  return smallest;
}

// True when the edge (cell, i, j) lies on the complex's boundary: a facet through it has one
// side in the complex and the other outside.
bool on_boundary(const Complex& complex, const Triangulation::Cell_handle& cell, int i, int j) {
  const Triangulation& triangulation = complex.triangulation();
  const auto c = cell->vertex(i);
  const auto d = cell->vertex(j);
  auto around = triangulation.incident_cells(Triangulation::Edge(cell, i, j));
  const auto first = around;
  do {
    if (complex.is_in_complex(around)) {
      for (int k = 0; k < 4; ++k) {
        const auto opposite = around->vertex(k);
        if (opposite == c || opposite == d) continue;  // the facet does not hold the edge
        if (!complex.is_in_complex(around->neighbor(k))) return true;
      }
    }
  } while (++around != first);
  return false;
}

// Removes the slivers that perturbation and exudation leave lying flat on the surface: a tet
// whose four vertices are surface vertices (none on a protected feature) and two of whose
// facets are on the boundary. Dropping it puts its two inner facets on the boundary instead,
// which stays a closed manifold unless the edge they share is already on it. Its volume is
// near zero, so the shape does not change. (A job's sampled mug kept one at 9.2 degrees: all
// four vertices on the handle's blend, where vertex moves found nothing better.)
void peel_surface_slivers(Complex& complex, double bound_deg) {
  std::vector<Triangulation::Cell_handle> slivers;
  for (auto cell = complex.cells_in_complex_begin(); cell != complex.cells_in_complex_end();
       ++cell) {
    if (min_dihedral_deg(cell) < bound_deg) slivers.push_back(cell);
  }
  for (const auto& cell : slivers) {
    std::array<int, 2> outer{};
    int boundary_facets = 0;
    bool on_surface = true;
    for (int k = 0; k < 4; ++k) {
      on_surface = on_surface && complex.in_dimension(cell->vertex(k)) == 2;
      if (!complex.is_in_complex(cell->neighbor(k))) {
        if (boundary_facets < 2) outer[static_cast<std::size_t>(boundary_facets)] = k;
        ++boundary_facets;
      }
    }
    // The inner facets are those opposite the two vertices off the outer facets' shared edge,
    // i.e. opposite neither outer[0] nor outer[1]; they share the edge (outer[0], outer[1]).
    if (!on_surface || boundary_facets != 2 || on_boundary(complex, cell, outer[0], outer[1])) {
      continue;
    }
    complex.remove_from_complex(cell);
  }
}

CgalMesh to_cgal_mesh(const SurfaceMesh& surface, const std::string& source) {
  std::optional<CgalMesh> mesh = cgal::to_cgal(surface);
  if (!mesh) {
    throw std::invalid_argument("cannot tetrahedralize " + source +
                                ": the surface is not manifold; repair it first "
                                "(geometry::repair_surface or `grip asset prepare`)");
  }
  return std::move(*mesh);
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

  Domain domain(mesh);
  domain.detect_features(options.feature_angle_deg);
  const double h = options.edge_length;
  const auto criteria_with = [&](const auto& cell_size) {
    return Criteria(params::edge_size = h, params::facet_angle = options.facet_angle_deg,
                    params::facet_size = h,
                    params::facet_distance = options.facet_distance_ratio * h,
                    params::cell_radius_edge_ratio = options.cell_radius_edge_ratio,
                    params::cell_size = cell_size);
  };
  std::optional<SignedDistance> depth;  // only a graded mesh needs it
  if (options.interior_growth > 0.0) depth.emplace(closed_surface);
  const Criteria criteria = depth
                                ? criteria_with(GradedCellSize{&*depth, h, options.interior_growth,
                                                               options.interior_size_ratio * h})
                                : criteria_with(h);
  Complex complex = initial_complex(closed_surface, domain, criteria, options);
  CGAL::refine_mesh_3(complex, domain, criteria, params::no_odt(), params::no_lloyd(),
                      params::no_perturb(), params::no_exude(), params::no_reset_c3t3());
  // Perturbation moves the vertices of slivers; exudation then re-weights what is left. With
  // no time limit both are functions of the mesh alone (perturbation's random moves come from
  // a generator with a fixed seed, its queue is ordered by vertex index), so the result does
  // not depend on the machine. Both stop by themselves: perturbation when every tet is above
  // the bound or no move improves any more, exudation when no re-weighting does.
  CGAL::perturb_mesh_3(complex, domain, params::sliver_bound = options.sliver_bound_deg,
                       params::time_limit = 0);
  CGAL::exude_mesh_3(complex, params::sliver_bound = options.sliver_bound_deg,
                     params::time_limit = 0);
  peel_surface_slivers(complex, options.sliver_bound_deg);

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
    throw std::runtime_error("tetrahedralizing " + source + " produced no tets: the edge length " +
                             std::to_string(h) +
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
    if ((x1 - x0).cross(x2 - x0).dot(x3 - x0) < 0.0)
      std::swap(result.tets(row, 2), result.tets(row, 3));
  }
  return result;
}

}  // namespace grip::geometry
