#include "src/geometry/signed_distance.hpp"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Simple_cartesian.h>
#include <tbb/parallel_for.h>

#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "src/geometry/cgal_surface_mesh.hpp"

namespace grip::geometry {
namespace {

using Kernel = cgal::Kernel;
using Point = cgal::Point;
using CgalMesh = cgal::SurfaceMesh;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<CgalMesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
using Inside = CGAL::Side_of_triangle_mesh<CgalMesh, Kernel, CGAL::Default, Tree>;

// Distances in plain double arithmetic: the closest-point search compares distances to
// neighbouring triangles, which tie wherever a point's closest point is on a shared edge (every
// point near a box's face diagonal). Exact predicates settle each tie in multiprecision, for the
// same distance either way; the inside test keeps them.
using DistanceKernel = CGAL::Simple_cartesian<double>;
using DistanceTriangles = std::vector<DistanceKernel::Triangle_3>;
using DistancePrimitive =
    CGAL::AABB_triangle_primitive<DistanceKernel, DistanceTriangles::const_iterator>;
using DistanceTree = CGAL::AABB_tree<CGAL::AABB_traits<DistanceKernel, DistancePrimitive>>;

}  // namespace

struct SignedDistance::Impl {
  CgalMesh mesh;
  Tree tree;
  std::unique_ptr<Inside> inside;  // holds a pointer to `tree`, so Impl never moves
  DistanceTriangles triangles;     // the distance tree's primitives point into it
  DistanceTree distance_tree;
};

SignedDistance::SignedDistance(const SurfaceMesh& closed_surface)
    : impl_(std::make_unique<Impl>()) {
  std::optional<CgalMesh> mesh = cgal::to_cgal(closed_surface);
  if (closed_surface.triangles.rows() == 0 || !mesh) {
    throw std::invalid_argument(
        "signed distance needs a non-empty manifold surface; repair the mesh first");
  }
  impl_->mesh = std::move(*mesh);
  if (!CGAL::is_closed(impl_->mesh)) {
    throw std::invalid_argument(
        "signed distance needs a closed surface (inside and outside); this one has open "
        "borders: repair the mesh first");
  }
  const auto face_range = CGAL::faces(impl_->mesh);
  impl_->tree.insert(face_range.first, face_range.second, impl_->mesh);
  impl_->tree.build();
  impl_->inside = std::make_unique<Inside>(impl_->tree);
  const auto corner = [&](int t, int k) {
    const Eigen::Vector3d v = closed_surface.vertices.row(closed_surface.triangles(t, k));
    return DistanceKernel::Point_3(v.x(), v.y(), v.z());
  };
  for (int t = 0; t < closed_surface.triangles.rows(); ++t) {
    impl_->triangles.emplace_back(corner(t, 0), corner(t, 1), corner(t, 2));
  }
  impl_->distance_tree.insert(impl_->triangles.cbegin(), impl_->triangles.cend());
  impl_->distance_tree.build();
  impl_->distance_tree.accelerate_distance_queries();
}

SignedDistance::~SignedDistance() = default;
SignedDistance::SignedDistance(SignedDistance&&) noexcept = default;
SignedDistance& SignedDistance::operator=(SignedDistance&&) noexcept = default;

double SignedDistance::operator()(const Eigen::Vector3d& point) const {
  const double distance = std::sqrt(impl_->distance_tree.squared_distance(
      DistanceKernel::Point_3(point.x(), point.y(), point.z())));
  switch ((*impl_->inside)(Point(point.x(), point.y(), point.z()))) {
    case CGAL::ON_BOUNDED_SIDE:
      return distance;
    case CGAL::ON_UNBOUNDED_SIDE:
      return -distance;
    default:
      return 0.0;
  }
}

Eigen::Vector3d SignedDistance::closest_point(const Eigen::Vector3d& point) const {
  const DistanceKernel::Point_3 q =
      impl_->distance_tree.closest_point(DistanceKernel::Point_3(point.x(), point.y(), point.z()));
  return {q.x(), q.y(), q.z()};
}

Eigen::VectorXd SignedDistance::evaluate(const Vertices& points) const {
  Eigen::VectorXd result(points.rows());
  tbb::parallel_for(Eigen::Index{0}, points.rows(),
                    [&](Eigen::Index i) { result[i] = (*this)(points.row(i).transpose()); });
  return result;
}

Eigen::Matrix<double, 2, 3> SignedDistance::bounds() const {
  const CGAL::Bbox_3 box = impl_->tree.bbox();
  Eigen::Matrix<double, 2, 3> result;
  result << box.xmin(), box.ymin(), box.zmin(), box.xmax(), box.ymax(), box.zmax();
  return result;
}

}  // namespace grip::geometry
