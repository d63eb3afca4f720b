// The only translation unit of the CCD benchmark that includes CGAL (slow to compile).
#include "bench/ccd/exact_separation.hpp"

#include <CGAL/Gmpq.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/squared_distance_3.h>

namespace grip::bench {

namespace {

using Kernel = CGAL::Simple_cartesian<CGAL::Gmpq>;
using Point = Kernel::Point_3;

// x0 + t (x1 - x0) in exact rationals (a double converts to Gmpq without rounding).
Point position_at(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1, const CGAL::Gmpq& t) {
  CGAL::Gmpq c[3];
  for (int axis = 0; axis < 3; ++axis) {
    const CGAL::Gmpq a(x0[axis]);
    c[axis] = a + t * (CGAL::Gmpq(x1[axis]) - a);
  }
  return Point(c[0], c[1], c[2]);
}

CGAL::Gmpq squared_distance(const Point (&v)[4], CcdQueryType type) {
  return type == CcdQueryType::kVertexFace
             ? CGAL::squared_distance(v[0], Kernel::Triangle_3(v[1], v[2], v[3]))
             : CGAL::squared_distance(Kernel::Segment_3(v[0], v[1]), Kernel::Segment_3(v[2], v[3]));
}

}  // namespace

bool exactly_separated_at(const CcdQuery& query, CcdQueryType type, double t,
                          double min_separation) {
  const CGAL::Gmpq time(t);
  Point v[4];
  for (int i = 0; i < 4; ++i) v[i] = position_at(query.vertices[i], query.vertices[i + 4], time);
  const CGAL::Gmpq xi(min_separation);
  return squared_distance(v, type) > xi * xi;
}

bool exactly_touching_at_start(const RationalCcdQuery& query, CcdQueryType type) {
  Point v[4];
  for (int i = 0; i < 4; ++i) {
    const auto& x = query.vertices[i];
    v[i] = Point(CGAL::Gmpq(x[0].get_mpq_t()), CGAL::Gmpq(x[1].get_mpq_t()),
                 CGAL::Gmpq(x[2].get_mpq_t()));
  }
  return CGAL::is_zero(squared_distance(v, type));
}

}  // namespace grip::bench
