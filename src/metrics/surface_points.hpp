#pragma once
// Points fixed on a (possibly deforming) surface: sampled once, area-uniform, on the rest
// mesh, and carried by barycentric coordinates so they follow any later vertex positions.
// D1/D2 evaluate the object's signed distance at such points on the gripper.
#include <cstdint>

#include <Eigen/Core>

#include "src/geometry/mesh.hpp"

namespace grip::metrics {

class SurfacePoints {
 public:
  // Samples `count` points on `rest` (geometry::sample_surface: same mesh, count and seed,
  // same points). Throws std::invalid_argument for a mesh of zero area or a negative count.
  SurfacePoints(const geometry::SurfaceMesh& rest, int count, std::uint64_t seed);

  int size() const { return static_cast<int>(corners_.rows()); }

  // The points on the surface whose vertices are at `vertices` (the rest mesh's order).
  geometry::Vertices positions(const geometry::Vertices& vertices) const;

 private:
  geometry::Triangles corners_;  // the three vertices of each point's triangle
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> weights_;  // barycentric
};

}  // namespace grip::metrics
