#include "src/geometry/primitives.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace grip::geometry {
namespace {

// A solid of revolution about the x axis from a profile of (x, r) pairs ordered by x; the first
// and last profile points may have r = 0 (poles). Faces point away from the axis.
SurfaceMesh revolve_about_x(const std::vector<Eigen::Vector2d>& profile, int segments) {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;
  // Each profile point becomes one pole vertex (r == 0) or a ring of `segments` vertices.
  std::vector<int> first;  // index of the first vertex of each profile point's ring
  std::vector<bool> pole;
  for (const Eigen::Vector2d& p : profile) {
    first.push_back(static_cast<int>(vertices.size()));
    pole.push_back(p.y() == 0.0);
    if (p.y() == 0.0) {
      vertices.emplace_back(p.x(), 0.0, 0.0);
      continue;
    }
    for (int s = 0; s < segments; ++s) {
      const double angle = 2.0 * std::numbers::pi * s / segments;
      vertices.emplace_back(p.x(), p.y() * std::cos(angle), p.y() * std::sin(angle));
    }
  }
  // Quad (ring k, s), (ring k, s+1), (ring k+1, s+1), (ring k+1, s) split in two; with the
  // angle increasing from +y to +z, this order is counter-clockwise seen from outside.
  for (std::size_t k = 0; k + 1 < profile.size(); ++k) {
    for (int s = 0; s < segments; ++s) {
      const int t = (s + 1) % segments;
      const int a = pole[k] ? first[k] : first[k] + s;
      const int b = pole[k] ? first[k] : first[k] + t;
      const int c = pole[k + 1] ? first[k + 1] : first[k + 1] + s;
      const int d = pole[k + 1] ? first[k + 1] : first[k + 1] + t;
      if (!pole[k]) triangles.emplace_back(a, b, c);
      if (!pole[k + 1]) triangles.emplace_back(b, d, c);
    }
  }
  SurfaceMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(vertices.size()), 3);
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    mesh.vertices.row(static_cast<Eigen::Index>(i)) = vertices[i].transpose();
  }
  mesh.triangles.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    mesh.triangles.row(static_cast<Eigen::Index>(i)) = triangles[i].transpose();
  }
  return mesh;
}

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

}  // namespace

SurfaceMesh make_box(const Eigen::Vector3d& size) {
  require((size.array() > 0.0).all(), "make_box: every edge length must be positive");
  const Eigen::Vector3d h = 0.5 * size;
  SurfaceMesh mesh;
  mesh.vertices.resize(8, 3);
  for (int i = 0; i < 8; ++i) {
    mesh.vertices.row(i) << ((i & 1) ? h.x() : -h.x()), ((i & 2) ? h.y() : -h.y()),
        ((i & 4) ? h.z() : -h.z());
  }
  mesh.triangles.resize(12, 3);
  mesh.triangles << 0, 2, 3, 0, 3, 1,  // -z
      4, 5, 7, 4, 7, 6,                // +z
      0, 1, 5, 0, 5, 4,                // -y
      2, 6, 7, 2, 7, 3,                // +y
      0, 4, 6, 0, 6, 2,                // -x
      1, 3, 7, 1, 7, 5;                // +x
  return mesh;
}

SurfaceMesh make_capsule(double radius, double length, int segments, int rings) {
  require(radius > 0.0 && length >= 2.0 * radius,
          "make_capsule: need radius > 0 and length >= 2 * radius");
  require(segments >= 3 && rings >= 1, "make_capsule: need segments >= 3 and rings >= 1");
  std::vector<Eigen::Vector2d> profile;
  for (int k = 0; k <= rings; ++k) {  // cap at x = 0, from the pole to the equator
    const double a = 0.5 * std::numbers::pi * (1.0 - static_cast<double>(k) / rings);
    profile.emplace_back(radius - radius * std::sin(a), radius * std::cos(a));
  }
  const bool sphere = length == 2.0 * radius;
  for (int k = sphere ? 1 : 0; k <= rings; ++k) {  // cap at x = length, equator to pole
    const double a = 0.5 * std::numbers::pi * static_cast<double>(k) / rings;
    profile.emplace_back(length - radius + radius * std::sin(a), radius * std::cos(a));
  }
  profile.front().y() = 0.0;
  profile.back().y() = 0.0;
  return revolve_about_x(profile, segments);
}

SurfaceMesh make_cylinder(double radius, double length, int segments) {
  require(radius > 0.0 && length > 0.0, "make_cylinder: need radius > 0 and length > 0");
  require(segments >= 3, "make_cylinder: need segments >= 3");
  SurfaceMesh mesh =
      revolve_about_x({{0.0, 0.0}, {0.0, radius}, {length, radius}, {length, 0.0}}, segments);
  // Revolved about x from 0 to length; turn x into z and centre it (a proper rotation: x->z,
  // y->x, z->y keeps the orientation).
  geometry::Vertices rotated(mesh.vertices.rows(), 3);
  rotated.col(0) = mesh.vertices.col(1);
  rotated.col(1) = mesh.vertices.col(2);
  rotated.col(2) = mesh.vertices.col(0).array() - 0.5 * length;
  mesh.vertices = rotated;
  return mesh;
}

SurfaceMesh make_sphere(double radius, int segments, int rings) {
  SurfaceMesh mesh = make_capsule(radius, 2.0 * radius, segments, rings);
  mesh.vertices.col(0).array() -= radius;
  return mesh;
}

}  // namespace grip::geometry
