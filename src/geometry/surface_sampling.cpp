#include "src/geometry/surface_sampling.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

namespace grip::geometry {

// CGAL's Random_points_in_triangle_mesh_3 draws the same distribution but returns points
// only; the metrics need each point's triangle and normal, hence this short sampler.
SurfaceSamples sample_surface(const SurfaceMesh& mesh, int count, std::uint64_t seed) {
  if (count < 0) throw std::invalid_argument("surface sampling: negative sample count");
  const Eigen::Index faces = mesh.triangles.rows();
  std::vector<double> cumulative_area(static_cast<std::size_t>(faces));
  Vertices unit_normals(faces, 3);
  double total = 0.0;
  for (Eigen::Index f = 0; f < faces; ++f) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.triangles(f, 0));
    const Eigen::Vector3d b = mesh.vertices.row(mesh.triangles(f, 1));
    const Eigen::Vector3d c = mesh.vertices.row(mesh.triangles(f, 2));
    const Eigen::Vector3d cross = (b - a).cross(c - a);
    const double twice_area = cross.norm();
    total += twice_area / 2.0;
    cumulative_area[static_cast<std::size_t>(f)] = total;
    unit_normals.row(f) = twice_area > 0.0 ? Eigen::RowVector3d(cross.transpose() / twice_area)
                                           : Eigen::RowVector3d::Zero();
  }
  if (!(total > 0.0)) {
    throw std::invalid_argument("surface sampling: the mesh has zero area");
  }
  std::mt19937_64 generator(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  SurfaceSamples samples;
  samples.points.resize(count, 3);
  samples.normals.resize(count, 3);
  samples.faces.resize(count);
  for (int s = 0; s < count; ++s) {
    const double target = uniform(generator) * total;
    const auto it = std::upper_bound(cumulative_area.begin(), cumulative_area.end(), target);
    const Eigen::Index f = std::min<Eigen::Index>(it - cumulative_area.begin(), faces - 1);
    // Uniform on a triangle: with r1, r2 uniform, sqrt(r1) makes the density linear in the
    // distance from corner a, which the area element requires.
    const double r1 = std::sqrt(uniform(generator));
    const double r2 = uniform(generator);
    const Eigen::RowVector3d a = mesh.vertices.row(mesh.triangles(f, 0));
    const Eigen::RowVector3d b = mesh.vertices.row(mesh.triangles(f, 1));
    const Eigen::RowVector3d c = mesh.vertices.row(mesh.triangles(f, 2));
    samples.points.row(s) = (1.0 - r1) * a + r1 * (1.0 - r2) * b + r1 * r2 * c;
    samples.normals.row(s) = unit_normals.row(f);
    samples.faces[s] = static_cast<int>(f);
  }
  return samples;
}

}  // namespace grip::geometry
