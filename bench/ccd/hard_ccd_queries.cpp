#include "bench/ccd/hard_ccd_queries.hpp"

#include <array>
#include <utility>

namespace grip::bench {

namespace {

using Q = mpq_class;
using Vec = std::array<Q, 3>;

// One hand-built query in a canonical frame, before scaling and reorientation.
struct Case {
  std::array<Vec, kCcdQueryRows> v;  // 4 vertices at t = 0, then the same 4 at t = 1
  bool collides;
  // The answer hinges on exact coordinates (contact exactly at an endpoint of the interval, on
  // an edge, a 2^-40 margin, coplanar motion): only transformed by exact dyadic operations.
  // Contact at t = 0 does not: rounding moves it by round-off, and t = 0 stays the answer.
  bool exact;
};

Vec vec(const Q& x, const Q& y, const Q& z) { return {x, y, z}; }
Vec add(const Vec& a, const Vec& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }

const Q kHalf(1, 2);
const Q kQuarter(1, 4);
const Q kEighth(1, 8);
// 2^-40 ~ 9.1e-13: the near-miss and near-hit margin.
const Q kTiny = Q(1) / Q(mpz_class(1) << 40);
const Q kFast(10000);

Case moving(const std::array<Vec, 4>& at0, const std::array<Vec, 4>& at1, bool collides,
            bool exact) {
  Case c{{}, collides, exact};
  for (int i = 0; i < 4; ++i) {
    c.v[i] = at0[i];
    c.v[i + 4] = at1[i];
  }
  return c;
}

// Point p0 -> p1 against the static triangle (0,0,0), (1,0,0), (0,1,0) in the plane z = 0.
Case point_vs_unit_triangle(const Vec& p0, const Vec& p1, bool collides, bool exact) {
  const Vec a = vec(0, 0, 0), b = vec(1, 0, 0), c = vec(0, 1, 0);
  return moving({p0, a, b, c}, {p1, a, b, c}, collides, exact);
}

std::vector<Case> vertex_face_cases() {
  const Vec a = vec(0, 0, 0), b = vec(1, 0, 0), c = vec(0, 1, 0);
  const Vec shift = vec(3, -2, 5);
  const Vec up = vec(0, 0, 2);
  auto shifted = [&](const Vec& p) { return add(p, shift); };
  return {
      // Through the interior, and beside the triangle.
      point_vs_unit_triangle(vec(kQuarter, kQuarter, 1), vec(kQuarter, kQuarter, -1), true, false),
      point_vs_unit_triangle(vec(1, 1, 1), vec(1, 1, -1), false, false),
      // Contact exactly at t = 1.
      point_vs_unit_triangle(vec(kQuarter, kQuarter, 1), vec(kQuarter, kQuarter, 0), true, true),
      // Through an edge's midpoint, through a vertex, through the hypotenuse.
      point_vs_unit_triangle(vec(kHalf, 0, 1), vec(kHalf, 0, -1), true, true),
      point_vs_unit_triangle(vec(1, 0, 1), vec(1, 0, -1), true, true),
      point_vs_unit_triangle(vec(kHalf, kHalf, 1), vec(kHalf, kHalf, -1), true, true),
      // Coplanar: sliding through the triangle, past it, and onto an edge at t = 1.
      point_vs_unit_triangle(vec(-1, kQuarter, 0), vec(2, kQuarter, 0), true, true),
      point_vs_unit_triangle(vec(-1, 2, 0), vec(2, 2, 0), false, false),
      point_vs_unit_triangle(vec(kHalf, -1, 0), vec(kHalf, 0, 0), true, true),
      // Zero relative motion: apart, and touching throughout.
      moving({vec(kQuarter, kQuarter, kEighth), a, b, c},
             {shifted(vec(kQuarter, kQuarter, kEighth)), shifted(a), shifted(b), shifted(c)}, false,
             false),
      moving({vec(kQuarter, kQuarter, 0), a, b, c},
             {shifted(vec(kQuarter, kQuarter, 0)), shifted(a), shifted(b), shifted(c)}, true, true),
      // Missing or hitting an edge by 2^-40, stopping 2^-40 short or passing 2^-40 through.
      point_vs_unit_triangle(vec(kHalf, -kTiny, 1), vec(kHalf, -kTiny, -1), false, true),
      point_vs_unit_triangle(vec(kHalf, kTiny, 1), vec(kHalf, kTiny, -1), true, true),
      point_vs_unit_triangle(vec(kQuarter, kQuarter, 1), vec(kQuarter, kQuarter, kTiny), false,
                             true),
      point_vs_unit_triangle(vec(kQuarter, kQuarter, 1), vec(kQuarter, kQuarter, -kTiny), true,
                             true),
      point_vs_unit_triangle(vec(-kTiny, -kTiny, 1), vec(-kTiny, -kTiny, -1), false, true),
      // Fast motion: through the triangle, and passing over it at height 1/2.
      point_vs_unit_triangle(vec(kQuarter, kQuarter, kFast), vec(kQuarter, kQuarter, -kFast), true,
                             false),
      point_vs_unit_triangle(vec(-kFast, kQuarter, kHalf), vec(kFast, kQuarter, kHalf), false,
                             false),
      // The triangle sweeps over a static point.
      moving({vec(kQuarter, kQuarter, 0), vec(0, 0, -1), vec(1, 0, -1), vec(0, 1, -1)},
             {vec(kQuarter, kQuarter, 0), vec(0, 0, 1), vec(1, 0, 1), vec(0, 1, 1)}, true, false),
      // Rotating triangle (vertex c rises to z = 2): its plane crosses (1/8, 1/2, 1/2) at
      // t = 1/2 with barycentric weights (3/8, 1/8, 1/2); a point at x = 2 lies outside.
      moving({vec(kEighth, kHalf, kHalf), a, b, c}, {vec(kEighth, kHalf, kHalf), a, b, add(c, up)},
             true, false),
      moving({vec(2, kHalf, kHalf), a, b, c}, {vec(2, kHalf, kHalf), a, b, add(c, up)}, false,
             false),
  };
}

// Touching at t = 0 (answer: collision at t = 0, however rounding moves the contact), and
// starting 2^-40 away (a gap).
std::vector<Case> vertex_face_touching_cases() {
  const Vec a = vec(0, 0, 0), b = vec(1, 0, 0), c = vec(0, 1, 0);
  return {
      // Touching at t = 0 on the face: moving away, sliding within it, moving through it.
      point_vs_unit_triangle(vec(kQuarter, kQuarter, 0), vec(kQuarter, kQuarter, 1), true, false),
      point_vs_unit_triangle(vec(kQuarter, kQuarter, 0), vec(kHalf, kQuarter, 0), true, false),
      point_vs_unit_triangle(vec(kQuarter, kQuarter, 0), vec(kQuarter, kQuarter, -1), true, false),
      // Touching at t = 0 on an edge (moving away along the normal, and outward in the plane),
      // on the hypotenuse, on a vertex; the triangle leaving a point that rests on it.
      point_vs_unit_triangle(vec(kHalf, 0, 0), vec(kHalf, 0, 1), true, false),
      point_vs_unit_triangle(vec(kHalf, 0, 0), vec(kHalf, -1, 0), true, false),
      point_vs_unit_triangle(vec(kHalf, kHalf, 0), vec(1, 1, 1), true, false),
      point_vs_unit_triangle(vec(1, 0, 0), vec(2, -1, 1), true, false),
      moving({vec(kQuarter, kQuarter, 0), a, b, c},
             {vec(kQuarter, kQuarter, 0), add(a, vec(0, 0, -1)), add(b, vec(0, 0, -1)),
              add(c, vec(0, 0, -1))},
             true, false),
      // Touching at t = 0 a tilted triangle (plane z = y / 3, normal (0, -1, 3)), on the face
      // and on an edge, moving away and through: rounding moves these contacts off the plane.
      moving({vec(Q(1, 5), Q(3, 5), Q(1, 5)), a, b, vec(0, 3, 1)},
             {vec(Q(1, 5), Q(-2, 5), Q(16, 5)), a, b, vec(0, 3, 1)}, true, false),
      moving({vec(Q(1, 5), Q(3, 5), Q(1, 5)), a, b, vec(0, 3, 1)},
             {vec(Q(1, 5), Q(8, 5), Q(-14, 5)), a, b, vec(0, 3, 1)}, true, false),
      moving({vec(Q(4, 5), Q(3, 5), Q(1, 5)), a, b, vec(0, 3, 1)},
             {vec(Q(4, 5), Q(-2, 5), Q(16, 5)), a, b, vec(0, 3, 1)}, true, false),
      // Starting 2^-40 above the face and moving away: a gap, not a touching start.
      point_vs_unit_triangle(vec(kQuarter, kQuarter, kTiny), vec(kQuarter, kQuarter, 1), false,
                             true),
  };
}

// Edge a moving against the static edge b from (0,-1,0) to (0,1,0).
Case edge_vs_unit_edge(const Vec& a0, const Vec& a1, const Vec& a0_end, const Vec& a1_end,
                       bool collides, bool exact) {
  const Vec b0 = vec(0, -1, 0), b1 = vec(0, 1, 0);
  return moving({a0, a1, b0, b1}, {a0_end, a1_end, b0, b1}, collides, exact);
}

// Edge a along x at height z0 (from x = x_lo to x_hi, at y) moving to height z1.
Case edge_along_x(const Q& x_lo, const Q& x_hi, const Q& y, const Q& z0, const Q& z1, bool collides,
                  bool exact) {
  return edge_vs_unit_edge(vec(x_lo, y, z0), vec(x_hi, y, z0), vec(x_lo, y, z1), vec(x_hi, y, z1),
                           collides, exact);
}

std::vector<Case> edge_edge_cases() {
  const Vec shift = vec(5, 5, 5);
  auto shifted = [&](const Vec& p) { return add(p, shift); };
  const Vec b0 = vec(0, -1, 0), b1 = vec(0, 1, 0);
  return {
      // Crossing interiors, and passing beyond b's end.
      edge_along_x(-1, 1, 0, 1, -1, true, false),
      edge_along_x(-1, 1, 3, 1, -1, false, false),
      // Contact exactly at t = 1.
      edge_along_x(-1, 1, 0, 1, 0, true, true),
      // An endpoint of a through b's interior; endpoint through endpoint.
      edge_along_x(0, 1, kHalf, 1, -1, true, true),
      edge_along_x(0, 1, 1, 1, -1, true, true),
      // Beyond b's endpoint by 2^-40, and within it by 2^-40.
      edge_along_x(0, 1, 1 + kTiny, 1, -1, false, true),
      edge_along_x(0, 1, 1 - kTiny, 1, -1, true, true),
      // Stopping 2^-40 short of b, and passing 2^-40 through.
      edge_along_x(-1, 1, 0, 1, kTiny, false, true),
      edge_along_x(-1, 1, 0, 1, -kTiny, true, true),
      // Parallel edges (both along y): overlapping sweep, and a sweep 2^-40 to the side.
      edge_vs_unit_edge(vec(0, -kHalf, 1), vec(0, kHalf, 1), vec(0, -kHalf, -1), vec(0, kHalf, -1),
                        true, true),
      edge_vs_unit_edge(vec(kTiny, -kHalf, 1), vec(kTiny, kHalf, 1), vec(kTiny, -kHalf, -1),
                        vec(kTiny, kHalf, -1), false, true),
      // Collinear (both on the y axis): overlapping at t = 0, meeting end to end at t = 1, and
      // stopping 1/2 short.
      edge_vs_unit_edge(vec(0, kHalf, 0), vec(0, 2, 0), vec(0, kHalf + 1, 0), vec(0, 3, 0), true,
                        true),
      edge_vs_unit_edge(vec(0, 3, 0), vec(0, 4, 0), vec(0, 1, 0), vec(0, 2, 0), true, true),
      edge_vs_unit_edge(vec(0, 4, 0), vec(0, 5, 0), vec(0, kHalf + 1, 0), vec(0, kHalf + 2, 0),
                        false, false),
      // Zero relative motion: crossing throughout, and apart throughout.
      moving({vec(-1, 0, 0), vec(1, 0, 0), b0, b1},
             {shifted(vec(-1, 0, 0)), shifted(vec(1, 0, 0)), shifted(b0), shifted(b1)}, true, true),
      moving({vec(-1, 0, kEighth), vec(1, 0, kEighth), b0, b1},
             {shifted(vec(-1, 0, kEighth)), shifted(vec(1, 0, kEighth)), shifted(b0), shifted(b1)},
             false, false),
      // Fast motion through b.
      edge_along_x(-1, 1, 0, kFast, -kFast, true, false),
      // Rotating edge: a0 sinks to z = -3 while a1 stays, crossing b at t = 1/2; pivoting the
      // other way it never reaches b.
      edge_vs_unit_edge(vec(-1, 0, 1), vec(1, 0, 1), vec(-1, 0, -3), vec(1, 0, 1), true, false),
      edge_vs_unit_edge(vec(-1, 0, 1), vec(1, 0, 1), vec(-1, 0, 3), vec(1, 0, 1), false, false),
      // Both edges move: a down, b up, crossing at t = 1/2.
      moving({vec(-1, 0, 1), vec(1, 0, 1), vec(0, -1, -1), vec(0, 1, -1)},
             {vec(-1, 0, -1), vec(1, 0, -1), vec(0, -1, 1), vec(0, 1, 1)}, true, false),
  };
}

// Touching at t = 0 (answer: collision at t = 0, however rounding moves the contact), and
// starting 2^-40 away (a gap).
std::vector<Case> edge_edge_touching_cases() {
  return {
      // Crossing at t = 0: moving away, moving through, sliding along b.
      edge_along_x(-1, 1, 0, 0, 1, true, false),
      edge_along_x(-1, 1, 0, 0, -1, true, false),
      edge_vs_unit_edge(vec(-1, 0, 0), vec(1, 0, 0), vec(-1, kHalf, 0), vec(1, kHalf, 0), true,
                        false),
      // Touching at t = 0 and moving away: an endpoint of a on b's interior, endpoint on
      // endpoint, collinear and overlapping (moving sideways), collinear end to end (moving
      // along the line).
      edge_along_x(0, 1, kHalf, 0, 1, true, false),
      edge_along_x(0, 1, 1, 0, 1, true, false),
      edge_vs_unit_edge(vec(0, kHalf, 0), vec(0, 2, 0), vec(1, kHalf, 1), vec(1, 2, 1), true,
                        false),
      edge_vs_unit_edge(vec(0, 1, 0), vec(0, 2, 0), vec(0, 2, 0), vec(0, 3, 0), true, false),
      // Touching at t = 0 a tilted edge from (0,0,0) to (3,5,7) at (3/5, 1, 7/5), crossing it
      // and with an endpoint on it, moving away along the common normal (-7, -7, 8).
      moving({vec(Q(1, 5), Q(7, 5), Q(7, 5)), vec(Q(6, 5), Q(2, 5), Q(7, 5)), vec(0, 0, 0),
              vec(3, 5, 7)},
             {vec(Q(-34, 5), Q(-28, 5), Q(47, 5)), vec(Q(-29, 5), Q(-33, 5), Q(47, 5)),
              vec(0, 0, 0), vec(3, 5, 7)},
             true, false),
      moving(
          {vec(Q(3, 5), 1, Q(7, 5)), vec(Q(8, 5), 0, Q(7, 5)), vec(0, 0, 0), vec(3, 5, 7)},
          {vec(Q(-32, 5), -6, Q(47, 5)), vec(Q(-27, 5), -7, Q(47, 5)), vec(0, 0, 0), vec(3, 5, 7)},
          true, false),
      // Starting 2^-40 above b and moving away: a gap, not a touching start.
      edge_along_x(-1, 1, 0, kTiny, 1, false, true),
  };
}

// Reorientations that keep every coordinate exact: a cyclic axis permutation, optionally the
// mirror x -> -x, and a reordering of the primitives' vertices.
Case reoriented(const Case& c, int variant, CcdQueryType type) {
  Case out = c;
  for (Vec& v : out.v) {
    const Vec copy = v;
    for (int axis = 0; axis < 3; ++axis) v[axis] = copy[(axis + variant) % 3];
    if (variant == 2) v[0] = -v[0];
  }
  for (int half = 0; half < 2; ++half) {
    Vec* q = &out.v[4 * half];
    if (type == CcdQueryType::kVertexFace && variant == 1) std::swap(q[2], q[3]);
    if (type == CcdQueryType::kEdgeEdge && variant == 1) {
      std::swap(q[0], q[2]);
      std::swap(q[1], q[3]);
    }
    if (type == CcdQueryType::kEdgeEdge && variant == 2) std::swap(q[0], q[1]);
  }
  return out;
}

RationalCcdQuery scaled(const Case& c, const Q& scale, const Vec& offset) {
  RationalCcdQuery q;
  for (std::size_t row = 0; row < kCcdQueryRows; ++row) {
    for (int axis = 0; axis < 3; ++axis)
      q.vertices[row][axis] = scale * (c.v[row][axis] + offset[axis]);
  }
  q.collides = c.collides;
  return q;
}

}  // namespace

std::vector<RationalCcdQuery> hard_ccd_queries(CcdQueryType type) {
  std::vector<Case> cases =
      type == CcdQueryType::kVertexFace ? vertex_face_cases() : edge_edge_cases();
  const std::vector<Case> touching =
      type == CcdQueryType::kVertexFace ? vertex_face_touching_cases() : edge_edge_touching_cases();
  cases.insert(cases.end(), touching.begin(), touching.end());
  // Dyadic scales keep exact contacts exact in double: 2^-20 ~ 1e-6, 2^13 ~ 1e4.
  const Q dyadic_scales[] = {Q(1), Q(1) / Q(mpz_class(1) << 20), Q(mpz_class(1) << 13)};
  // Non-dyadic scales and offsets round in double; used only where the answer has a margin.
  const Q decimal_scales[] = {Q(1, 1000000), Q(10000)};
  const Vec no_offset = vec(0, 0, 0);
  const Vec odd_offset = vec(Q(1, 3), Q(-2, 7), Q(5, 11));
  std::vector<RationalCcdQuery> queries;
  for (const Case& base : cases) {
    for (int variant = 0; variant < 3; ++variant) {
      const Case c = reoriented(base, variant, type);
      for (const Q& scale : dyadic_scales) queries.push_back(scaled(c, scale, no_offset));
      if (!c.exact) {
        queries.push_back(scaled(c, Q(1), odd_offset));
        for (const Q& scale : decimal_scales) queries.push_back(scaled(c, scale, odd_offset));
      }
    }
  }
  return queries;
}

}  // namespace grip::bench
