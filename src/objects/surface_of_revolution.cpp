#include "src/objects/surface_of_revolution.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "src/geometry/mesh_measures.hpp"

namespace grip::objects {
namespace {

geometry::SurfaceMesh assemble(const std::vector<Eigen::Vector3d>& points,
                               const std::vector<Eigen::Vector3i>& triangles) {
  geometry::SurfaceMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) {
    mesh.vertices.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  }
  mesh.triangles.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    mesh.triangles.row(static_cast<Eigen::Index>(f)) = triangles[f].transpose();
  }
  // The winding follows the profile's direction; flip everything if it came out inward.
  if (geometry::surface_volume(mesh) < 0.0) {
    mesh.triangles.col(1).swap(mesh.triangles.col(2));
  }
  return mesh;
}

// Quads between ring a and ring b (each `n` consecutive vertices starting there), split in two.
// Ring a's edges run j+1 -> j and ring b's j -> j+1, which fixes the fans' winding below.
void connect_rings(std::vector<Eigen::Vector3i>& triangles, int a, int b, int n) {
  for (int j = 0; j < n; ++j) {
    const int j1 = (j + 1) % n;
    triangles.emplace_back(a + j, b + j, b + j1);
    triangles.emplace_back(a + j, b + j1, a + j1);
  }
}

void fan(std::vector<Eigen::Vector3i>& triangles, int pole, int ring, int n, bool reverse) {
  for (int j = 0; j < n; ++j) {
    const int j1 = (j + 1) % n;
    if (reverse) {
      triangles.emplace_back(pole, ring + j1, ring + j);
    } else {
      triangles.emplace_back(pole, ring + j, ring + j1);
    }
  }
}

}  // namespace

void append_arc(std::vector<Eigen::Vector2d>& profile, const Eigen::Vector2d& centre, double radius,
                double from, double to, int steps, bool include_start) {
  for (int i = include_start ? 0 : 1; i <= steps; ++i) {
    const double angle = from + (to - from) * i / steps;
    profile.push_back(centre + radius * Eigen::Vector2d(std::cos(angle), std::sin(angle)));
  }
}

geometry::SurfaceMesh revolve_profile(const std::vector<Eigen::Vector2d>& profile, int segments,
                                      bool closed_loop) {
  const int m = static_cast<int>(profile.size());
  if (segments < 3 || m < 3) {
    throw std::invalid_argument("revolve_profile: needs at least 3 segments and 3 profile points");
  }
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector3i> triangles;
  auto add_ring = [&](const Eigen::Vector2d& rz) {
    const int start = static_cast<int>(points.size());
    for (int j = 0; j < segments; ++j) {
      const double angle = 2.0 * std::numbers::pi * j / segments;
      points.emplace_back(rz.x() * std::cos(angle), rz.x() * std::sin(angle), rz.y());
    }
    return start;
  };
  if (closed_loop) {
    std::vector<int> rings;
    for (const auto& rz : profile) {
      if (!(rz.x() > 0.0))
        throw std::invalid_argument("revolve_profile: a loop must avoid the axis");
      rings.push_back(add_ring(rz));
    }
    for (int i = 0; i < m; ++i) connect_rings(triangles, rings[i], rings[(i + 1) % m], segments);
  } else {
    if (profile.front().x() != 0.0 || profile.back().x() != 0.0) {
      throw std::invalid_argument(
          "revolve_profile: an open profile must start and end on the axis");
    }
    const int bottom = 0;
    points.emplace_back(0.0, 0.0, profile.front().y());
    std::vector<int> rings;
    for (int i = 1; i + 1 < m; ++i) {
      if (!(profile[static_cast<std::size_t>(i)].x() > 0.0)) {
        throw std::invalid_argument("revolve_profile: only the profile's ends may touch the axis");
      }
      rings.push_back(add_ring(profile[static_cast<std::size_t>(i)]));
    }
    const int top = static_cast<int>(points.size());
    points.emplace_back(0.0, 0.0, profile.back().y());
    fan(triangles, bottom, rings.front(), segments, false);
    for (std::size_t i = 0; i + 1 < rings.size(); ++i) {
      connect_rings(triangles, rings[i], rings[i + 1], segments);
    }
    fan(triangles, top, rings.back(), segments, true);
  }
  return assemble(points, triangles);
}

geometry::SurfaceMesh sweep_tube(const std::vector<Eigen::Vector3d>& path, double radius,
                                 int segments) {
  if (path.size() < 2 || segments < 3 || !(radius > 0.0)) {
    throw std::invalid_argument("sweep_tube: needs two path points, 3 segments, radius > 0");
  }
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector3i> triangles;
  const std::size_t n = path.size();
  // A frame carried along the path by projection (rotation-minimizing enough for smooth arcs).
  Eigen::Vector3d tangent = (path[1] - path[0]).normalized();
  Eigen::Vector3d normal = tangent.unitOrthogonal();
  std::vector<int> rings;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d next = path[std::min(i + 1, n - 1)];
    const Eigen::Vector3d previous = path[i == 0 ? 0 : i - 1];
    tangent = (next - previous).normalized();
    normal = (normal - normal.dot(tangent) * tangent).normalized();
    const Eigen::Vector3d binormal = tangent.cross(normal);
    rings.push_back(static_cast<int>(points.size()));
    for (int j = 0; j < segments; ++j) {
      const double angle = 2.0 * std::numbers::pi * j / segments;
      points.push_back(path[i] + radius * (std::cos(angle) * normal + std::sin(angle) * binormal));
    }
  }
  for (std::size_t i = 0; i + 1 < n; ++i)
    connect_rings(triangles, rings[i], rings[i + 1], segments);
  const int first_cap = static_cast<int>(points.size());
  points.push_back(path.front());
  const int last_cap = static_cast<int>(points.size());
  points.push_back(path.back());
  fan(triangles, first_cap, rings.front(), segments, false);
  fan(triangles, last_cap, rings.back(), segments, true);
  return assemble(points, triangles);
}

}  // namespace grip::objects
