#include "src/geometry/boolean_union.hpp"

#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "src/geometry/cgal_surface_mesh.hpp"

namespace grip::geometry {
namespace {

namespace pmp = CGAL::Polygon_mesh_processing;

cgal::SurfaceMesh closed_operand(const SurfaceMesh& surface, const std::string& what) {
  std::optional<cgal::SurfaceMesh> mesh = cgal::to_cgal(surface);
  if (!mesh) throw std::invalid_argument(what + ": an operand is not a manifold surface");
  if (!CGAL::is_closed(*mesh)) throw std::invalid_argument(what + ": an operand is not closed");
  return std::move(*mesh);
}

// The same surface numbered by its geometry alone: vertices in lexicographic order of their
// coordinates, each triangle started at its lowest vertex (its orientation kept), triangles in
// lexicographic order.
SurfaceMesh in_canonical_order(const SurfaceMesh& surface) {
  const Eigen::Index n = surface.vertices.rows();
  std::vector<Eigen::Index> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  const auto row = [&](Eigen::Index v) {
    return std::make_tuple(surface.vertices(v, 0), surface.vertices(v, 1), surface.vertices(v, 2));
  };
  std::sort(order.begin(), order.end(),
            [&](Eigen::Index a, Eigen::Index b) { return row(a) < row(b); });
  SurfaceMesh canonical;
  canonical.vertices.resize(n, 3);
  std::vector<int> renumbered(static_cast<std::size_t>(n));
  for (Eigen::Index k = 0; k < n; ++k) {
    canonical.vertices.row(k) = surface.vertices.row(order[static_cast<std::size_t>(k)]);
    renumbered[static_cast<std::size_t>(order[static_cast<std::size_t>(k)])] = static_cast<int>(k);
  }
  std::vector<std::array<int, 3>> triangles;
  triangles.reserve(static_cast<std::size_t>(surface.triangles.rows()));
  for (Eigen::Index f = 0; f < surface.triangles.rows(); ++f) {
    std::array<int, 3> t{};
    for (int c = 0; c < 3; ++c) {
      t[static_cast<std::size_t>(c)] =
          renumbered[static_cast<std::size_t>(surface.triangles(f, c))];
    }
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    triangles.push_back(t);
  }
  std::sort(triangles.begin(), triangles.end());
  canonical.triangles.resize(surface.triangles.rows(), 3);
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    for (int c = 0; c < 3; ++c) {
      canonical.triangles(static_cast<Eigen::Index>(f), c) =
          triangles[f][static_cast<std::size_t>(c)];
    }
  }
  return canonical;
}

}  // namespace

SurfaceMesh boolean_union(const SurfaceMesh& a, const SurfaceMesh& b, const std::string& what) {
  cgal::SurfaceMesh first = closed_operand(a, what);
  cgal::SurfaceMesh second = closed_operand(b, what);
  cgal::SurfaceMesh corefined;
  if (!pmp::corefine_and_compute_union(first, second, corefined)) {
    throw std::invalid_argument(what +
                                ": the union is not a valid solid (an operand "
                                "intersects itself or is not outward oriented)");
  }
  // Corefinement numbers its output in an order that depends on where its bounding boxes lie
  // in memory (box intersection identifies boxes by address): a job's mug came out in another
  // order on the third call in a process, and Mesh_3 then made another tet mesh of it (28,557
  // or 28,564 tets), so a dataset depended on which rank had meshed what before. Numbered by
  // its geometry, the union is a function of the operands alone.
  std::optional<cgal::SurfaceMesh> result =
      cgal::to_cgal(in_canonical_order(cgal::from_cgal(corefined)));
  if (!result) throw std::logic_error(what + ": renumbering the union broke its connectivity");
  // Corefinement leaves slivers of triangles along the intersection curve (edges down to
  // 1e-18 m, angles near 0 or 180 degrees), on which tetrahedralization degenerates. Needles
  // (longest edge over 20 times the shortest) whose short edge is under 0.2 mm are collapsed
  // and caps flipped; nothing an object's shape depends on is that small. At a ratio of 100,
  // seam triangles of 0.06 x 2 mm stayed and left a 2-degree sliver tet (sampled mug 5).
  pmp::experimental::remove_almost_degenerate_faces(
      faces(*result), *result,
      /*cap_threshold=*/std::cos(160.0 * CGAL_PI / 180.0),
      /*needle_threshold=*/20.0,
      /*collapse_length_threshold=*/2e-4);
  result->collect_garbage();
  return in_canonical_order(cgal::from_cgal(*result));
}

}  // namespace grip::geometry
