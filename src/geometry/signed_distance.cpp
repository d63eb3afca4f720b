#include "src/geometry/signed_distance.hpp"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Side_of_triangle_mesh.h>
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

}  // namespace

struct SignedDistance::Impl {
  CgalMesh mesh;
  Tree tree;
  std::unique_ptr<Inside> inside;  // holds a pointer to `tree`, so Impl never moves
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
  impl_->tree.accelerate_distance_queries();
  impl_->inside = std::make_unique<Inside>(impl_->tree);
}

SignedDistance::~SignedDistance() = default;
SignedDistance::SignedDistance(SignedDistance&&) noexcept = default;
SignedDistance& SignedDistance::operator=(SignedDistance&&) noexcept = default;

double SignedDistance::operator()(const Eigen::Vector3d& point) const {
  const Point p(point.x(), point.y(), point.z());
  const double distance = std::sqrt(impl_->tree.squared_distance(p));
  switch ((*impl_->inside)(p)) {
    case CGAL::ON_BOUNDED_SIDE:
      return distance;
    case CGAL::ON_UNBOUNDED_SIDE:
      return -distance;
    default:
      return 0.0;
  }
}

Eigen::Vector3d SignedDistance::closest_point(const Eigen::Vector3d& point) const {
  const Point q = impl_->tree.closest_point(Point(point.x(), point.y(), point.z()));
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
