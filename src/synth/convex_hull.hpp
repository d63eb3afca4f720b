#pragma once
// The convex hull of a point set as its facet planes (CGAL computes the hull), and the point
// where a ray from an interior centre leaves it: the dexterous optimizer starts its hands on an
// inflated copy of the hull in a random direction from the object's centroid.
#include <vector>

#include <Eigen/Core>

#include "src/geometry/mesh.hpp"

namespace grip::synth {

class ConvexHull {
 public:
  struct Plane {
    Eigen::Vector3d normal;  // unit, outward
    double offset = 0.0;     // normal . x = offset on the plane
  };
  struct Exit {
    Eigen::Vector3d point;   // on the hull
    Eigen::Vector3d normal;  // the outward normal of the facet it lies on
  };

  // Facets are identified by the set of input points on their plane, so the planes (and every
  // later query) do not depend on how CGAL orders or triangulates coplanar facets, which varies
  // from run to run. Throws std::invalid_argument if the points span no volume.
  explicit ConvexHull(const geometry::Vertices& points);

  const std::vector<Plane>& planes() const { return planes_; }
  const Eigen::Vector3d& centre() const { return centre_; }  // mean of the hull's points

  // Where the ray from centre() along `direction` (non-zero) leaves the hull.
  Exit exit(const Eigen::Vector3d& direction) const;

 private:
  std::vector<Plane> planes_;
  Eigen::Vector3d centre_;
};

}  // namespace grip::synth
