#include "src/geometry/intersections.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>

namespace grip::geometry {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, int>;

Kernel::Point_3 point(const Vertices& positions, int v) {
  return {positions(v, 0), positions(v, 1), positions(v, 2)};
}

Box box_of(const Vertices& positions, std::initializer_list<int> vertices, int id) {
  double lo[3], hi[3];
  for (int k = 0; k < 3; ++k) lo[k] = hi[k] = positions(*vertices.begin(), k);
  for (int v : vertices) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], positions(v, k));
      hi[k] = std::max(hi[k], positions(v, k));
    }
  }
  return Box(lo, hi, id);
}

}  // namespace

int count_intersections(const Vertices& positions, const Triangles& faces, const Edges& edges,
                        const std::vector<int>& vertex_body,
                        const std::function<bool(int, int)>& may_touch) {
  std::vector<Box> edge_boxes;
  std::vector<Box> face_boxes;
  for (int e = 0; e < edges.rows(); ++e) {
    edge_boxes.push_back(box_of(positions, {edges(e, 0), edges(e, 1)}, e));
  }
  for (int f = 0; f < faces.rows(); ++f) {
    face_boxes.push_back(box_of(positions, {faces(f, 0), faces(f, 1), faces(f, 2)}, f));
  }
  int count = 0;
  // Closed boxes: touching boxes are reported, so a touching pair is tested too.
  CGAL::box_intersection_d(
      edge_boxes.begin(), edge_boxes.end(), face_boxes.begin(), face_boxes.end(),
      [&](const Box& edge_box, const Box& face_box) {
        const int e0 = edges(edge_box.info(), 0), e1 = edges(edge_box.info(), 1);
        const auto face = faces.row(face_box.info());
        for (int k = 0; k < 3; ++k) {
          if (face[k] == e0 || face[k] == e1) return;
        }
        if (!may_touch(vertex_body[e0], vertex_body[face[0]])) return;
        const Kernel::Segment_3 segment(point(positions, e0), point(positions, e1));
        const Kernel::Triangle_3 triangle(point(positions, face[0]), point(positions, face[1]),
                                          point(positions, face[2]));
        if (CGAL::do_intersect(segment, triangle)) ++count;
      },
      std::ptrdiff_t(10), CGAL::Box_intersection_d::CLOSED);
  return count;
}

}  // namespace grip::geometry
