// Additive CCD: analytic times of impact for head-on approaches (where ACCD's answer is exactly
// (1 - s) (d0 - xi) / v), minimum separation, t_max, zero relative motion, contact at t = 0
// (also where round-off leaves a touching pair a hair apart), the iteration cap, and on random
// motions that the returned time never overshoots.
// (The exact-arithmetic safety check over the hard query set is in tests/bench.)
#include "solver/kernels/accd.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace {

using namespace grip::solver::kernels;
using Eigen::Vector3d;

// Point above the triangle z = 0 falling from z = 1 to z = -1 while the triangle rises by
// `rise`: relative speed 2 + rise, first contact at t = 1 / (2 + rise).
AccdResult falling_point(const AccdOptions& options, double rise = 0.0) {
  const Vector3d p0(0.2, 0.2, 1.0), p1(0.2, 0.2, -1.0);
  const Vector3d t0(0, 0, 0), t1(1, 0, 0), t2(0, 1, 0), up(0, 0, rise);
  return point_triangle_accd(p0, t0, t1, t2, p1, t0 + up, t1 + up, t2 + up, options);
}

TEST(Accd, HeadOnPointTriangleStopsAtRescaledTime) {
  // Each step closes (1 - s) of the gap exactly, so ACCD stops after the first step whose
  // successor would leave less than s of the starting gap: toi = (1 - s) * d0 / v.
  for (const double s : {0.1, 0.5}) {
    AccdOptions options;
    options.rescaling = s;
    const AccdResult r = falling_point(options);
    EXPECT_TRUE(r.impact);
    EXPECT_NEAR(r.toi, (1.0 - s) * 0.5, 1e-15);
    const AccdResult rising = falling_point(options, 2.0);
    EXPECT_TRUE(rising.impact);
    EXPECT_NEAR(rising.toi, (1.0 - s) * 0.25, 1e-15);
  }
}

TEST(Accd, MinimumSeparationIsKept) {
  AccdOptions options;
  options.min_separation = 0.25;
  const AccdResult r = falling_point(options);
  EXPECT_TRUE(r.impact);
  EXPECT_NEAR(r.toi, 0.9 * (1.0 - 0.25) / 2.0, 1e-15);
  // Starting within the minimum separation is an impact at t = 0.
  options.min_separation = 1.0;
  EXPECT_EQ(falling_point(options).toi, 0.0);
  EXPECT_TRUE(falling_point(options).impact);
}

TEST(Accd, NoImpactBeforeTmax) {
  AccdOptions options;
  options.t_max = 0.4;  // contact is at 0.5
  const AccdResult r = falling_point(options);
  EXPECT_FALSE(r.impact);
  EXPECT_EQ(r.toi, 0.4);

  // Sliding parallel to the triangle's plane at height h from distance d0 = sqrt(1 + h^2):
  // a miss while h stays above s d0; below it ACCD conservatively reports an impact.
  const Vector3d t0(0, 0, 0), t1(1, 0, 0), t2(0, 1, 0);
  for (const double h : {0.5, 0.2, 0.05}) {
    const AccdResult slide =
        point_triangle_accd(Vector3d(-1, 0.2, h), t0, t1, t2, Vector3d(2, 0.2, h), t0, t1, t2);
    const bool above_gap = h > 0.1 * std::sqrt(1.0 + h * h);
    EXPECT_EQ(slide.impact, !above_gap) << "h = " << h;
    EXPECT_EQ(slide.toi == 1.0, above_gap) << "h = " << h;
  }
}

TEST(Accd, ZeroRelativeMotionAndContactAtStart) {
  const Vector3d t0(0, 0, 0), t1(1, 0, 0), t2(0, 1, 0), p(0.2, 0.2, 1e-3);
  const Vector3d shift(123.0, -4.0, 17.0);
  const AccdResult still =
      point_triangle_accd(p, t0, t1, t2, p + shift, t0 + shift, t1 + shift, t2 + shift);
  EXPECT_FALSE(still.impact);
  EXPECT_EQ(still.toi, 1.0);
  EXPECT_EQ(still.iterations, 0);

  // A point on the triangle at t = 0, moving away: contact already at t = 0.
  const Vector3d on(0.2, 0.2, 0.0);
  const AccdResult touching =
      point_triangle_accd(on, t0, t1, t2, on + Vector3d(0, 0, 1), t0, t1, t2);
  EXPECT_TRUE(touching.impact);
  EXPECT_EQ(touching.toi, 0.0);
  // Two edges crossing at t = 0.
  const AccdResult crossing =
      edge_edge_accd(Vector3d(-1, 0, 0), Vector3d(1, 0, 0), Vector3d(0, -1, 0), Vector3d(0, 1, 0),
                     Vector3d(-1, 0, 1), Vector3d(1, 0, 1), Vector3d(0, -1, 0), Vector3d(0, 1, 0));
  EXPECT_TRUE(crossing.impact);
  EXPECT_EQ(crossing.toi, 0.0);
}

// A triangle with no axis-aligned or dyadic structure, so points placed on it in double
// precision are off it by round-off (~1e-17), on either side.
struct SkewTriangle {
  Vector3d t0{0.1, 0.2, 0.3}, t1{1.3, 0.7, -0.2}, t2{0.4, 1.1, 0.9};
  Vector3d normal() const { return (t1 - t0).cross(t2 - t0).normalized(); }
  Vector3d at(double b1, double b2) const { return t0 + b1 * (t1 - t0) + b2 * (t2 - t0); }
};

// Moving away, sliding along, and moving into the primitive a start touches.
std::vector<Vector3d> directions(const Vector3d& normal, const Vector3d& tangent) {
  return {normal, tangent, -normal, 0.5 * normal + tangent};
}

TEST(Accd, PointTouchingTriangleWithinRoundOffIsImpactAtStart) {
  // On the face, on each edge, on each vertex; at unit scale, and scaled by 1e-3 and offset by
  // 1e3 (the round-off is relative to the coordinates).
  const SkewTriangle tri;
  const Vector3d n = tri.normal();
  const Vector3d along = (tri.t1 - tri.t0).normalized();
  struct Frame {
    double scale;
    Vector3d offset;
  };
  for (const Frame& f : {Frame{1.0, Vector3d::Zero()}, Frame{1e-3, Vector3d(1e3, -2e3, 5e2)}}) {
    const Vector3d t0 = f.scale * tri.t0 + f.offset, t1 = f.scale * tri.t1 + f.offset,
                   t2 = f.scale * tri.t2 + f.offset;
    std::vector<Vector3d> on;
    for (const double a : {0.1, 0.2, 1.0 / 3.0, 0.7}) {
      on.push_back(tri.at(a, 0.5 * (1.0 - a)));  // face
      on.push_back(tri.at(a, 0.0));              // edge t0 t1
      on.push_back(tri.at(0.0, a));              // edge t0 t2
      on.push_back(tri.at(a, 1.0 - a));          // edge t1 t2
    }
    on.push_back(tri.t0);
    on.push_back(tri.t1);
    on.push_back(tri.t2);
    for (std::size_t i = 0; i < on.size(); ++i) {
      const Vector3d p = f.scale * on[i] + f.offset;
      for (const Vector3d& d : directions(n, along)) {
        const AccdResult r = point_triangle_accd(p, t0, t1, t2, p + f.scale * d, t0, t1, t2);
        EXPECT_TRUE(r.impact) << "scale " << f.scale << ", point " << i << ", motion "
                              << d.transpose();
        EXPECT_EQ(r.toi, 0.0) << "scale " << f.scale << ", point " << i << ", motion "
                              << d.transpose();
      }
      // The triangle moving instead of the point.
      const AccdResult r = point_triangle_accd(p, t0, t1, t2, p, t0 - f.scale * n, t1 - f.scale * n,
                                               t2 - f.scale * n);
      EXPECT_TRUE(r.impact && r.toi == 0.0) << "scale " << f.scale << ", point " << i;
    }
  }
}

TEST(Accd, EdgesTouchingWithinRoundOffAreImpactAtStart) {
  const Vector3d a0(0.1, 0.2, 0.3), a1(1.3, 0.7, -0.2), dir_b(0.3, 0.1, 0.7);
  const Vector3d n = (a1 - a0).cross(dir_b).normalized();
  const Vector3d along_a = (a1 - a0).normalized();
  struct Pair {
    const char* what;
    Vector3d b0, b1;
  };
  std::vector<Pair> pairs;
  for (const double s : {0.1, 0.3, 1.0 / 3.0, 0.7}) {
    const Vector3d c = a0 + s * (a1 - a0);
    pairs.push_back({"crossing", c - 0.7 * dir_b, c + 0.6 * dir_b});
    pairs.push_back({"endpoint on interior", c, c + dir_b});
    // Collinear: overlapping, and meeting end to end (b starts where a ends).
    pairs.push_back({"collinear overlapping", c, a1 + s * (a1 - a0)});
    pairs.push_back({"collinear end to end", a1, a1 + s * (a1 - a0)});
  }
  pairs.push_back({"endpoint on endpoint", a1, a1 + dir_b});
  for (const Pair& pair : pairs) {
    for (const Vector3d& d : directions(n, along_a)) {
      const AccdResult r =
          edge_edge_accd(a0, a1, pair.b0, pair.b1, a0 + d, a1 + d, pair.b0, pair.b1);
      EXPECT_TRUE(r.impact) << pair.what << ", motion " << d.transpose();
      EXPECT_EQ(r.toi, 0.0) << pair.what << ", motion " << d.transpose();
    }
  }
}

TEST(Accd, StartAtTheMinimumSeparationWithinRoundOffIsImpactAtStart) {
  // A point xi above the face (up to round-off), moving away or sliding: contact at t = 0.
  const SkewTriangle tri;
  const Vector3d n = tri.normal();
  const Vector3d along = (tri.t2 - tri.t1).normalized();
  AccdOptions options;
  options.min_separation = 0.01;
  for (int k = 1; k <= 9; ++k) {
    const double a = 0.05 * k;
    const Vector3d p = tri.at(a, a) + options.min_separation * n;
    for (const Vector3d& d : {n, along}) {
      const AccdResult r =
          point_triangle_accd(p, tri.t0, tri.t1, tri.t2, p + d, tri.t0, tri.t1, tri.t2, options);
      EXPECT_TRUE(r.impact) << "a = " << a << ", motion " << d.transpose();
      EXPECT_EQ(r.toi, 0.0) << "a = " << a << ", motion " << d.transpose();
    }
  }
}

TEST(Accd, SmallGapsAboveRoundOffAreNotContact) {
  // Apart by 1e-11 of the coordinates' magnitude (far above round-off): moving away is a miss,
  // moving in is an impact after t = 0, at unit scale and at 1e4.
  for (const double scale : {1.0, 1e4}) {
    const Vector3d t0(0, 0, 0), t1(scale, 0, 0), t2(0, scale, 0);
    const Vector3d p(0.25 * scale, 0.25 * scale, 1e-11 * scale), up(0, 0, scale);
    const AccdResult away = point_triangle_accd(p, t0, t1, t2, p + up, t0, t1, t2);
    EXPECT_FALSE(away.impact) << scale;
    EXPECT_EQ(away.toi, 1.0) << scale;
    const AccdResult in = point_triangle_accd(p, t0, t1, t2, p - up, t0, t1, t2);
    EXPECT_TRUE(in.impact) << scale;
    EXPECT_GT(in.toi, 0.0) << scale;
    EXPECT_LT(in.toi, 1e-11) << scale;
    // The band's edge: m = scale here, so half the band is contact and twice it is a gap.
    for (const double k : {0.5, 2.0}) {
      const Vector3d q(0.25 * scale, 0.25 * scale, k * kAccdTouchingRoundoff * scale);
      const AccdResult r = point_triangle_accd(q, t0, t1, t2, q + up, t0, t1, t2);
      EXPECT_EQ(r.impact, k < 1.0) << scale << ", " << k;
      EXPECT_EQ(r.toi, k < 1.0 ? 0.0 : 1.0) << scale << ", " << k;
    }
  }
}

TEST(Accd, HeadOnEdgeEdge) {
  // Edge a along x at z = 1 moves to z = -1 through edge b along y at z = 0: contact at 0.5.
  const AccdResult r = edge_edge_accd(Vector3d(-1, 0, 1), Vector3d(1, 0, 1), Vector3d(0, -1, 0),
                                      Vector3d(0, 1, 0), Vector3d(-1, 0, -1), Vector3d(1, 0, -1),
                                      Vector3d(0, -1, 0), Vector3d(0, 1, 0));
  EXPECT_TRUE(r.impact);
  EXPECT_NEAR(r.toi, 0.45, 1e-15);
  // The same edges shifted apart along y by 3 pass each other without contact.
  const Vector3d y(0, 3, 0);
  const AccdResult miss = edge_edge_accd(
      Vector3d(-1, 0, 1) + y, Vector3d(1, 0, 1) + y, Vector3d(0, -1, 0), Vector3d(0, 1, 0),
      Vector3d(-1, 0, -1) + y, Vector3d(1, 0, -1) + y, Vector3d(0, -1, 0), Vector3d(0, 1, 0));
  EXPECT_FALSE(miss.impact);
  EXPECT_EQ(miss.toi, 1.0);
}

TEST(Accd, IterationCapAnswersTheLastSafeTime) {
  AccdOptions options;
  options.max_iterations = 1;
  const AccdResult r = falling_point(options);
  EXPECT_TRUE(r.impact);
  EXPECT_EQ(r.iterations, 1);
  EXPECT_NEAR(r.toi, 0.45, 1e-15);
  options.max_iterations = 0;
  EXPECT_TRUE(falling_point(options).impact);
  EXPECT_EQ(falling_point(options).toi, 0.0);
}

// Random linear motions: on [0, toi] the pair never touches (dense sampling), and a reported
// miss really stays apart on [0, 1] (sampled).
TEST(Accd, RandomMotionsNeverOvershoot) {
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto random_point = [&](double scale) -> Vector3d {
    return Vector3d(u(rng), u(rng), u(rng)) * scale;
  };
  int impacts = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    Vector3d x0[4], x1[4];
    for (int i = 0; i < 4; ++i) {
      x0[i] = random_point(1.0);
      x1[i] = x0[i] + random_point(2.0);
    }
    const bool edge_edge = trial % 2 == 1;
    auto distance_sq = [&](double t) {
      Vector3d v[4];
      for (int i = 0; i < 4; ++i) v[i] = x0[i] + t * (x1[i] - x0[i]);
      return edge_edge ? edge_edge_distance_sq(v[0], v[1], v[2], v[3])
                       : point_triangle_distance_sq(v[0], v[1], v[2], v[3]);
    };
    if (distance_sq(0.0) < 1e-6) continue;
    const AccdResult r =
        edge_edge ? edge_edge_accd(x0[0], x0[1], x0[2], x0[3], x1[0], x1[1], x1[2], x1[3])
                  : point_triangle_accd(x0[0], x0[1], x0[2], x0[3], x1[0], x1[1], x1[2], x1[3]);
    ASSERT_GE(r.toi, 0.0);
    ASSERT_LE(r.toi, 1.0);
    impacts += r.impact;
    const double end = r.impact ? r.toi : 1.0;
    double min_d_sq = distance_sq(0.0);
    constexpr int kSamples = 400;
    for (int k = 1; k <= kSamples; ++k)
      min_d_sq = std::min(min_d_sq, distance_sq(end * k / kSamples));
    ASSERT_GT(min_d_sq, 0.0) << "trial " << trial;
    if (r.impact) {
      // Stopping rule: every accepted time keeps d >= s d0 (s = 0.1), up to round-off.
      EXPECT_GE(distance_sq(r.toi), 0.99 * 0.01 * distance_sq(0.0)) << "trial " << trial;
    }
  }
  // The set mixes hits and misses.
  EXPECT_GT(impacts, 200);
  EXPECT_LT(impacts, 1800);
}

}  // namespace
