#pragma once
// Exact signed distance to a closed surface: an AABB tree gives the unsigned distance to the
// nearest triangle and a ray-parity test (CGAL Side_of_triangle_mesh) gives the sign.
//
// Sign convention: POSITIVE INSIDE the object, negative outside, zero on the surface. This is
// the paper's d^o, so D1 = max(0, max_p d(p)) is the deepest penetration of a point set and
// D2 = |max_p d(p)| its distance to the object (see metrics/).
#include <memory>

#include <Eigen/Core>

#include "src/geometry/mesh.hpp"

namespace grip::geometry {

class SignedDistance {
 public:
  // `closed_surface` must be closed and outward oriented (repair_surface makes it so); throws
  // std::invalid_argument if it has open borders. The mesh is copied; building costs
  // O(n log n) once.
  explicit SignedDistance(const SurfaceMesh& closed_surface);
  ~SignedDistance();
  SignedDistance(SignedDistance&&) noexcept;
  SignedDistance& operator=(SignedDistance&&) noexcept;
  SignedDistance(const SignedDistance&) = delete;
  SignedDistance& operator=(const SignedDistance&) = delete;

  // Signed distance of one point (m), positive inside. Thread-safe.
  double operator()(const Eigen::Vector3d& point) const;

  // The nearest surface point to `point`. Thread-safe.
  Eigen::Vector3d closest_point(const Eigen::Vector3d& point) const;

  // Signed distances of many points (rows of `points`), in parallel; the result does not
  // depend on the number of threads.
  Eigen::VectorXd evaluate(const Vertices& points) const;

  // Axis-aligned bounds of the surface: rows are min and max corners.
  Eigen::Matrix<double, 2, 3> bounds() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace grip::geometry
