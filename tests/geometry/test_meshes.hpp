#pragma once
// Small closed meshes built in code for the geometry tests (tests make their own inputs).
#include <cmath>
#include <numbers>

#include "src/geometry/mesh.hpp"

namespace grip::geometry::testing {

// Axis-aligned box [-hx, hx] x [-hy, hy] x [-hz, hz], 12 outward triangles.
inline SurfaceMesh box(double hx, double hy, double hz) {
  SurfaceMesh mesh;
  mesh.vertices.resize(8, 3);
  for (int i = 0; i < 8; ++i) {
    mesh.vertices.row(i) << ((i & 1) ? hx : -hx), ((i & 2) ? hy : -hy), ((i & 4) ? hz : -hz);
  }
  mesh.triangles.resize(12, 3);
  mesh.triangles << 0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4, 2, 6, 7, 2, 7, 3, 0, 4, 6,
      0, 6, 2, 1, 3, 7, 1, 7, 5;
  return mesh;
}

// Latitude-longitude sphere of radius r about the origin with all vertices on the sphere:
// `rings` latitude steps and `segments` longitude steps, outward triangles.
inline SurfaceMesh uv_sphere(double r, int rings, int segments) {
  SurfaceMesh mesh;
  const int n = 2 + (rings - 1) * segments;
  mesh.vertices.resize(n, 3);
  mesh.vertices.row(0) << 0.0, 0.0, -r;
  for (int i = 1; i < rings; ++i) {
    const double polar = std::numbers::pi * i / rings;
    for (int j = 0; j < segments; ++j) {
      const double azimuth = 2.0 * std::numbers::pi * j / segments;
      mesh.vertices.row(1 + (i - 1) * segments + j) << r * std::sin(polar) * std::cos(azimuth),
          r * std::sin(polar) * std::sin(azimuth), -r * std::cos(polar);
    }
  }
  mesh.vertices.row(n - 1) << 0.0, 0.0, r;
  const int faces = 2 * segments + 2 * (rings - 2) * segments;
  mesh.triangles.resize(faces, 3);
  int f = 0;
  auto ring = [&](int i, int j) { return 1 + (i - 1) * segments + (j % segments); };
  for (int j = 0; j < segments; ++j) mesh.triangles.row(f++) << 0, ring(1, j + 1), ring(1, j);
  for (int i = 1; i + 1 < rings; ++i) {
    for (int j = 0; j < segments; ++j) {
      mesh.triangles.row(f++) << ring(i, j), ring(i, j + 1), ring(i + 1, j + 1);
      mesh.triangles.row(f++) << ring(i, j), ring(i + 1, j + 1), ring(i + 1, j);
    }
  }
  for (int j = 0; j < segments; ++j) {
    mesh.triangles.row(f++) << n - 1, ring(rings - 1, j), ring(rings - 1, j + 1);
  }
  return mesh;
}

}  // namespace grip::geometry::testing
