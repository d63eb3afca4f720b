#pragma once
// Seeded, area-uniform random points on a triangle surface, with the outward normal of the
// triangle each lies on (the D1/D2 metric samples 50,000 such points on a gripper).
#include <cstdint>

#include <Eigen/Core>

#include "src/geometry/mesh.hpp"

namespace grip::geometry {

struct SurfaceSamples {
  Vertices points;        // one sample per row (m)
  Vertices normals;       // unit normal of the sample's triangle
  Eigen::VectorXi faces;  // index of the sample's triangle
};

// Draws `count` points: a triangle with probability proportional to its area, then a point
// uniform on it. Same mesh, count and seed give the same samples. Throws
// std::invalid_argument for a mesh of zero area or a negative count.
SurfaceSamples sample_surface(const SurfaceMesh& mesh, int count, std::uint64_t seed);

}  // namespace grip::geometry
