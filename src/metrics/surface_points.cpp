#include "src/metrics/surface_points.hpp"

#include <Eigen/Geometry>

#include "src/geometry/surface_sampling.hpp"

namespace grip::metrics {

SurfacePoints::SurfacePoints(const geometry::SurfaceMesh& rest, int count, std::uint64_t seed) {
  const geometry::SurfaceSamples samples = geometry::sample_surface(rest, count, seed);
  corners_.resize(samples.points.rows(), 3);
  weights_.resize(samples.points.rows(), 3);
  for (Eigen::Index i = 0; i < samples.points.rows(); ++i) {
    const Eigen::Vector3i tri = rest.triangles.row(samples.faces[i]).transpose();
    corners_.row(i) = tri.transpose();
    const Eigen::Vector3d a = rest.vertices.row(tri[0]), b = rest.vertices.row(tri[1]),
                          c = rest.vertices.row(tri[2]);
    const Eigen::Vector3d p = samples.points.row(i);
    // Barycentric coordinates by sub-triangle areas (the point lies on the triangle).
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const double area2 = n.squaredNorm();
    const double wb = (p - a).cross(c - a).dot(n) / area2;
    const double wc = (b - a).cross(p - a).dot(n) / area2;
    weights_.row(i) << 1.0 - wb - wc, wb, wc;
  }
}

geometry::Vertices SurfacePoints::positions(const geometry::Vertices& vertices) const {
  geometry::Vertices points(corners_.rows(), 3);
  for (Eigen::Index i = 0; i < corners_.rows(); ++i) {
    points.row(i) = weights_(i, 0) * vertices.row(corners_(i, 0)) +
                    weights_(i, 1) * vertices.row(corners_(i, 1)) +
                    weights_(i, 2) * vertices.row(corners_(i, 2));
  }
  return points;
}

}  // namespace grip::metrics
