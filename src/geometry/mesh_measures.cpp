#include "src/geometry/mesh_measures.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <sstream>

namespace grip::geometry {

double surface_volume(const SurfaceMesh& mesh) {
  double six_volume = 0.0;
  for (Eigen::Index f = 0; f < mesh.triangles.rows(); ++f) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.triangles(f, 0));
    const Eigen::Vector3d b = mesh.vertices.row(mesh.triangles(f, 1));
    const Eigen::Vector3d c = mesh.vertices.row(mesh.triangles(f, 2));
    six_volume += a.dot(b.cross(c));
  }
  return six_volume / 6.0;
}

double surface_area(const SurfaceMesh& mesh) {
  double twice_area = 0.0;
  for (Eigen::Index f = 0; f < mesh.triangles.rows(); ++f) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.triangles(f, 0));
    const Eigen::Vector3d b = mesh.vertices.row(mesh.triangles(f, 1));
    const Eigen::Vector3d c = mesh.vertices.row(mesh.triangles(f, 2));
    twice_area += (b - a).cross(c - a).norm();
  }
  return twice_area / 2.0;
}

double bounding_box_diagonal(const Vertices& vertices) {
  if (vertices.rows() == 0) return 0.0;
  return (vertices.colwise().maxCoeff() - vertices.colwise().minCoeff()).norm();
}

std::string metric_scale_warning(const Vertices& vertices, const std::string& source) {
  constexpr double kSmallest = 1e-3;  // m
  constexpr double kLargest = 10.0;   // m
  const double diagonal = bounding_box_diagonal(vertices);
  if (diagonal >= kSmallest && diagonal <= kLargest) return {};
  std::ostringstream message;
  message << "'" << source << "' measures " << diagonal
          << " m across (bounding-box diagonal), outside the expected 1 mm to 10 m; ";
  if (diagonal > kLargest) {
    message << "if it is in millimetres, scale it by 0.001";
  } else {
    message << "if it is in kilometres or was shrunk, scale it by 1000";
  }
  return message.str();
}

}  // namespace grip::geometry
