#include "src/synth/triangle_tree.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/squared_distance_3.h>
#include <Eigen/Geometry>

#include <cmath>
#include <iterator>
#include <stdexcept>
#include <vector>

namespace grip::synth {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using TriangleIterator = std::vector<Triangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, TriangleIterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

Point to_point(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

Triangle triangle(const geometry::SurfaceMesh& mesh, int f) {
  const auto corner = [&](int k) {
    return to_point(mesh.vertices.row(mesh.triangles(f, k)).transpose());
  };
  return {corner(0), corner(1), corner(2)};
}

}  // namespace

struct TriangleTree::Impl {
  geometry::SurfaceMesh mesh;
  std::vector<Triangle> triangles;
  Tree tree;
};

TriangleTree::TriangleTree(const geometry::SurfaceMesh& mesh) : impl_(std::make_unique<Impl>()) {
  if (mesh.triangles.rows() == 0)
    throw std::invalid_argument("TriangleTree: the mesh has no triangles");
  impl_->mesh = mesh;
  impl_->triangles.reserve(static_cast<std::size_t>(mesh.triangles.rows()));
  for (int f = 0; f < mesh.triangles.rows(); ++f) impl_->triangles.push_back(triangle(mesh, f));
  impl_->tree.insert(impl_->triangles.cbegin(), impl_->triangles.cend());
  impl_->tree.build();
  impl_->tree.accelerate_distance_queries();
}

TriangleTree::~TriangleTree() = default;
TriangleTree::TriangleTree(TriangleTree&&) noexcept = default;
TriangleTree& TriangleTree::operator=(TriangleTree&&) noexcept = default;

TriangleTree::Closest TriangleTree::closest(const Eigen::Vector3d& point) const {
  const auto [p, id] = impl_->tree.closest_point_and_primitive(to_point(point));
  Closest result;
  result.point = Eigen::Vector3d(p.x(), p.y(), p.z());
  result.face = static_cast<int>(std::distance(impl_->triangles.cbegin(), id));
  result.distance = (result.point - point).norm();
  return result;
}

Eigen::Vector3d TriangleTree::face_normal(int face) const {
  const geometry::SurfaceMesh& m = impl_->mesh;
  const Eigen::Vector3d a = m.vertices.row(m.triangles(face, 0));
  const Eigen::Vector3d b = m.vertices.row(m.triangles(face, 1));
  const Eigen::Vector3d c = m.vertices.row(m.triangles(face, 2));
  return (b - a).cross(c - a).normalized();
}

TriangleTree::Proximity TriangleTree::proximity(const geometry::SurfaceMesh& other,
                                                double cutoff) const {
  Proximity result;
  result.distance = cutoff;
  double best_squared = cutoff * cutoff;
  std::vector<Tree::Primitive_id> near;
  for (int f = 0; f < other.triangles.rows(); ++f) {
    const Triangle t = triangle(other, f);
    const CGAL::Bbox_3 box = t.bbox();
    const CGAL::Bbox_3 grown(box.xmin() - cutoff, box.ymin() - cutoff, box.zmin() - cutoff,
                             box.xmax() + cutoff, box.ymax() + cutoff, box.zmax() + cutoff);
    near.clear();
    impl_->tree.all_intersected_primitives(grown, std::back_inserter(near));
    for (const TriangleIterator id : near) {
      const double squared = CGAL::to_double(CGAL::squared_distance(t, *id));
      if (squared < best_squared || (squared == 0.0 && !result.intersecting)) {
        best_squared = squared;
        result.face_other = f;
        result.face_here = static_cast<int>(std::distance(impl_->triangles.cbegin(), id));
        if (squared == 0.0) {
          result.intersecting = true;
          result.distance = 0.0;
          return result;
        }
      }
    }
  }
  result.distance = result.face_here >= 0 ? std::sqrt(best_squared) : cutoff;
  return result;
}

}  // namespace grip::synth
