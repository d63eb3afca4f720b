#include "src/synth/surface_frames.hpp"

#include <CGAL/Fuzzy_sphere.h>
#include <CGAL/Kd_tree.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <iterator>
#include <numeric>
#include <stdexcept>
#include <utility>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

namespace grip::synth {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using PointMap = CGAL::Pointer_property_map<Point>::const_type;
using Traits = CGAL::Search_traits_adapter<std::size_t, PointMap, CGAL::Search_traits_3<Kernel>>;
using Tree = CGAL::Kd_tree<Traits>;
using Sphere = CGAL::Fuzzy_sphere<Traits>;

}  // namespace

// The kd-tree holds cloud indices; the property map gives their points.
struct SurfaceFrames::Impl {
  std::vector<Point> points;
  std::unique_ptr<Tree> tree;
};

SurfaceFrames::SurfaceFrames(const geometry::SurfaceSamples& cloud, double radius)
    : cloud_(cloud), radius_(radius), impl_(std::make_unique<Impl>()) {
  if (!(radius > 0.0)) throw std::invalid_argument("SurfaceFrames: the radius must be positive");
  for (int i = 0; i < cloud_.points.rows(); ++i) {
    impl_->points.emplace_back(cloud_.points(i, 0), cloud_.points(i, 1), cloud_.points(i, 2));
  }
  std::vector<std::size_t> indices(impl_->points.size());
  std::iota(indices.begin(), indices.end(), std::size_t{0});
  impl_->tree =
      std::make_unique<Tree>(indices.begin(), indices.end(), Tree::Splitter(),
                             Traits(CGAL::make_property_map(std::as_const(impl_->points))));
  impl_->tree->build();  // searches are const and thread-safe once built
}

SurfaceFrames::~SurfaceFrames() = default;

std::vector<int> SurfaceFrames::neighbours(const Eigen::Vector3d& point) const {
  std::vector<std::size_t> found;
  impl_->tree->search(std::back_inserter(found), Sphere(Point(point.x(), point.y(), point.z()),
                                                        radius_, 0.0, impl_->tree->traits()));
  std::sort(found.begin(), found.end());
  return {found.begin(), found.end()};
}

SurfaceFrame SurfaceFrames::at(int index) const {
  SurfaceFrame frame;
  frame.point = cloud_.points.row(index).transpose();
  const Eigen::Vector3d own_normal = cloud_.normals.row(index).transpose();
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const int i : neighbours(frame.point)) {
    const Eigen::Vector3d n = cloud_.normals.row(i).transpose();
    scatter += n * n.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(scatter);  // ascending eigenvalues
  frame.normal = eigen.eigenvectors().col(2);
  if (frame.normal.dot(own_normal) < 0.0) frame.normal = -frame.normal;
  frame.curvature_axis = eigen.eigenvectors().col(0);
  frame.curvature_axis -= frame.curvature_axis.dot(frame.normal) * frame.normal;
  frame.curvature_axis.normalize();
  frame.binormal = frame.curvature_axis.cross(frame.normal);
  return frame;
}

}  // namespace grip::synth
