#include "src/synth/convex_hull.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>

#include <Eigen/Geometry>

namespace grip::synth {

ConvexHull::ConvexHull(const geometry::Vertices& points) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Point = Kernel::Point_3;
  // Input index of each distinct point (the smallest, for duplicates).
  std::map<std::array<double, 3>, int> index_of;
  std::vector<Point> input;
  for (int i = 0; i < points.rows(); ++i) {
    if (index_of.emplace(std::array<double, 3>{points(i, 0), points(i, 1), points(i, 2)}, i)
            .second) {
      input.emplace_back(points(i, 0), points(i, 1), points(i, 2));
    }
  }
  CGAL::Surface_mesh<Point> hull;
  CGAL::convex_hull_3(input.begin(), input.end(), hull);
  if (hull.number_of_faces() == 0) {
    throw std::invalid_argument("convex hull: the object's points span no volume");
  }
  std::vector<int> hull_points;
  for (const auto v : hull.vertices()) {
    const Point& p = hull.point(v);
    hull_points.push_back(index_of.at({p.x(), p.y(), p.z()}));
  }
  std::sort(hull_points.begin(), hull_points.end());
  centre_.setZero();
  for (const int i : hull_points) centre_ += points.row(i).transpose();
  centre_ /= static_cast<double>(hull_points.size());
  const double scale = (points.colwise().maxCoeff() - points.colwise().minCoeff()).norm();
  const double tolerance = 1e-9 * scale;

  // Each CGAL facet names a plane; the sorted set of hull points on it identifies the plane.
  std::set<std::vector<int>> facets;
  for (const auto face : hull.faces()) {
    std::vector<Eigen::Vector3d> corners;
    for (const auto v : CGAL::vertices_around_face(hull.halfedge(face), hull)) {
      const Point& p = hull.point(v);
      corners.emplace_back(p.x(), p.y(), p.z());
    }
    const Eigen::Vector3d n = (corners[1] - corners[0]).cross(corners[2] - corners[0]).normalized();
    std::vector<int> on_plane;
    for (const int i : hull_points) {
      if (std::abs(n.dot(points.row(i).transpose() - corners[0])) <= tolerance)
        on_plane.push_back(i);
    }
    facets.insert(on_plane);
  }
  // Fit each plane from its own point set: the first point, the farthest from it, and the one
  // spanning the largest triangle with them.
  for (const std::vector<int>& facet : facets) {
    const Eigen::Vector3d a = points.row(facet[0]).transpose();
    Eigen::Vector3d b = a, c = a;
    for (const int i : facet) {
      if ((points.row(i).transpose() - a).norm() > (b - a).norm()) b = points.row(i).transpose();
    }
    double best = 0.0;
    for (const int i : facet) {
      const double area = (b - a).cross(points.row(i).transpose() - a).norm();
      if (area > best) best = area, c = points.row(i).transpose();
    }
    Eigen::Vector3d n = (b - a).cross(c - a).normalized();
    if (n.dot(a - centre_) < 0.0) n = -n;
    planes_.push_back({n, n.dot(a)});
  }
}

ConvexHull::Exit ConvexHull::exit(const Eigen::Vector3d& direction) const {
  const Eigen::Vector3d u = direction.normalized();
  double nearest = std::numeric_limits<double>::infinity();
  const Plane* through = &planes_.front();
  for (const Plane& plane : planes_) {
    const double rate = plane.normal.dot(u);
    if (rate <= 0.0) continue;
    const double t = (plane.offset - plane.normal.dot(centre_)) / rate;
    if (t < nearest) nearest = t, through = &plane;
  }
  return {centre_ + nearest * u, through->normal};
}

}  // namespace grip::synth
