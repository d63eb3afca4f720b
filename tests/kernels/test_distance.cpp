// Distance kernels: classification on constructed cases, values against an independent exact
// reference (enumeration of face pairs of the two convex hulls), and every gradient and Hessian
// against central finite differences on random and near-degenerate configurations with distances
// from 1e-9 to 1.

#include <gtest/gtest.h>
#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "solver/kernels/distance.hpp"
#include "tests/kernels/finite_difference.hpp"

namespace {

using Eigen::Vector3d;
using grip::test::min_fd_gradient_error;
using grip::test::min_fd_jacobian_error;
namespace k = grip::solver::kernels;
using PE = k::PointEdgeDistanceType;
using PT = k::PointTriangleDistanceType;
using EE = k::EdgeEdgeDistanceType;
using Vec9 = Eigen::Matrix<double, 9, 1>;
using Vec12 = Eigen::Matrix<double, 12, 1>;

// ---------------------------------------------------------------------------------------------
// Independent reference: the squared distance between the convex hulls of A and B is the minimum,
// over every pair of faces (vertex subsets I of A and J of B), of the least-squares distance
// between the faces' affine hulls, counted only where the minimizer's barycentric weights are all
// non-negative. This shares no code or formula with the kernels.
struct HullDistance {
  double d_sq = std::numeric_limits<double>::infinity();
  unsigned a_support = 0, b_support = 0;  // vertex bitmasks of the minimizing face pair
  double margin = 0.0;                    // smallest barycentric weight of that pair
};

HullDistance hull_distance_sq(const std::vector<Vector3d>& A, const std::vector<Vector3d>& B) {
  HullDistance best;
  for (unsigned ma = 1; ma < (1u << A.size()); ++ma)
    for (unsigned mb = 1; mb < (1u << B.size()); ++mb) {
      std::vector<int> I, J;
      for (int i = 0; i < int(A.size()); ++i)
        if (ma & (1u << i)) I.push_back(i);
      for (int j = 0; j < int(B.size()); ++j)
        if (mb & (1u << j)) J.push_back(j);
      // X - Y = (A[I0] - B[J0]) + M z with z = (lambda_1.., mu_1..).
      const int cols = int(I.size() + J.size()) - 2;
      const Vector3d base = A[I[0]] - B[J[0]];
      Eigen::VectorXd weights_a(I.size()), weights_b(J.size());
      Vector3d diff = base;
      if (cols > 0) {
        Eigen::MatrixXd M(3, cols);
        int c = 0;
        for (std::size_t i = 1; i < I.size(); ++i) M.col(c++) = A[I[i]] - A[I[0]];
        for (std::size_t j = 1; j < J.size(); ++j) M.col(c++) = -(B[J[j]] - B[J[0]]);
        const Eigen::VectorXd z = M.completeOrthogonalDecomposition().solve(-base);
        diff = base + M * z;
        weights_a.tail(I.size() - 1) = z.head(I.size() - 1);
        weights_b.tail(J.size() - 1) = z.tail(J.size() - 1);
      } else {
        weights_a.resize(1);
        weights_b.resize(1);
      }
      weights_a[0] = 1.0 - weights_a.tail(I.size() - 1).sum();
      weights_b[0] = 1.0 - weights_b.tail(J.size() - 1).sum();
      const double margin = std::min(weights_a.minCoeff(), weights_b.minCoeff());
      if (margin < 0.0) continue;
      const double d = diff.squaredNorm();
      if (d < best.d_sq) best = {d, ma, mb, margin};
    }
  return best;
}

unsigned support_of(PE t) {
  switch (t) {
    case PE::P_E0:
      return 0b01;
    case PE::P_E1:
      return 0b10;
    default:
      return 0b11;
  }
}
unsigned support_of(PT t) {
  switch (t) {
    case PT::P_T0:
      return 0b001;
    case PT::P_T1:
      return 0b010;
    case PT::P_T2:
      return 0b100;
    case PT::P_E0:
      return 0b011;
    case PT::P_E1:
      return 0b110;
    case PT::P_E2:
      return 0b101;
    default:
      return 0b111;
  }
}
std::pair<unsigned, unsigned> support_of(EE t) {
  switch (t) {
    case EE::EA0_EB0:
      return {0b01, 0b01};
    case EE::EA0_EB1:
      return {0b01, 0b10};
    case EE::EA1_EB0:
      return {0b10, 0b01};
    case EE::EA1_EB1:
      return {0b10, 0b10};
    case EE::EA_EB0:
      return {0b11, 0b01};
    case EE::EA_EB1:
      return {0b11, 0b10};
    case EE::EA0_EB:
      return {0b01, 0b11};
    case EE::EA1_EB:
      return {0b10, 0b11};
    default:
      return {0b11, 0b11};
  }
}

// ---------------------------------------------------------------------------------------------
// Random configurations. Coordinates are O(1); "d" is a prescribed distance, log-uniform in
// [1e-9, 1], between the primitives.
class Random {
 public:
  explicit Random(std::uint64_t seed) : rng_(seed) {}
  double uniform(double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng_);
  }
  double log_uniform(double lo, double hi) { return std::exp(uniform(std::log(lo), std::log(hi))); }
  double distance() { return log_uniform(1e-9, 1.0); }
  Vector3d point() { return Vector3d(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)); }
  Vector3d unit() {
    for (;;) {
      const Vector3d v = point();
      if (v.squaredNorm() > 1e-2 && v.squaredNorm() <= 1.0) return v.normalized();
    }
  }
  // A unit vector perpendicular to v.
  Vector3d unit_perpendicular(const Vector3d& v) {
    for (;;) {
      const Vector3d c = v.cross(unit());
      if (c.squaredNorm() > 1e-2 * v.squaredNorm()) return c.normalized();
    }
  }
  // A triangle whose angles all have sin > 0.1: the kernels' non-degenerate regime.
  std::array<Vector3d, 3> triangle() {
    for (;;) {
      const std::array<Vector3d, 3> t = {point(), point(), point()};
      bool ok = true;
      for (int i = 0; i < 3; ++i) {
        const Vector3d a = t[(i + 1) % 3] - t[i], b = t[(i + 2) % 3] - t[i];
        ok = ok && a.cross(b).squaredNorm() > 1e-2 * a.squaredNorm() * b.squaredNorm() &&
             a.squaredNorm() > 1e-2;
      }
      if (ok) return t;
    }
  }

 private:
  std::mt19937_64 rng_;
};

// Point p, edge e0 e1.
struct PointEdge {
  Vector3d p, e0, e1;
};
// Point p, triangle t0 t1 t2.
struct PointTriangle {
  Vector3d p, t0, t1, t2;
};
// Edges ea0 ea1 and eb0 eb1.
struct EdgeEdge {
  Vector3d ea0, ea1, eb0, eb1;
};

std::vector<PointEdge> point_edge_configurations(Random& r, int per_family) {
  std::vector<PointEdge> out;
  for (int i = 0; i < per_family; ++i) {
    const Vector3d e0 = r.point(), e1 = r.point();
    const Vector3d e = e1 - e0;
    // Interior at distance d.
    out.push_back(
        {e0 + r.uniform(0.05, 0.95) * e + r.distance() * r.unit_perpendicular(e), e0, e1});
    // Near an endpoint.
    out.push_back({(i % 2 ? e0 : e1) + r.distance() * r.unit(), e0, e1});
    // Generic.
    out.push_back({r.point(), e0, e1});
  }
  return out;
}

std::vector<PointTriangle> point_triangle_configurations(Random& r, int per_family) {
  std::vector<PointTriangle> out;
  for (int i = 0; i < per_family; ++i) {
    const auto t = r.triangle();
    const Vector3d n = (t[1] - t[0]).cross(t[2] - t[0]).normalized();
    // Above the face interior.
    const double b1 = r.uniform(0.05, 0.9), b2 = r.uniform(0.05, 0.95 - b1);
    const Vector3d foot = t[0] + b1 * (t[1] - t[0]) + b2 * (t[2] - t[0]);
    out.push_back({foot + (i % 2 ? 1.0 : -1.0) * r.distance() * n, t[0], t[1], t[2]});
    // Near edge k, off it in the half-space of directions away from the face.
    const int kk = i % 3;
    const Vector3d a = t[kk], b = t[(kk + 1) % 3], c = t[(kk + 2) % 3];
    const Vector3d along = (b - a).normalized();
    Vector3d outward = (a - c) - (a - c).dot(along) * along;
    outward.normalize();
    const double phi = r.uniform(0.0, std::numbers::pi);
    out.push_back({a + r.uniform(0.05, 0.95) * (b - a) +
                       r.distance() * (std::cos(phi) * n + std::sin(phi) * outward),
                   t[0], t[1], t[2]});
    // Near vertex k.
    out.push_back({t[kk] + r.distance() * r.unit(), t[0], t[1], t[2]});
    // Generic.
    out.push_back({r.point(), t[0], t[1], t[2]});
  }
  return out;
}

std::vector<EdgeEdge> edge_edge_configurations(Random& r, int per_family, bool with_parallel) {
  std::vector<EdgeEdge> out;
  for (int i = 0; i < per_family; ++i) {
    const Vector3d ea0 = r.point(), ea1 = r.point();
    const Vector3d a = ea1 - ea0;
    // Crossing: the common perpendicular joins interior points at distance d.
    {
      const Vector3d b = r.unit_perpendicular(a) + r.uniform(-1, 1) * a.normalized();
      const Vector3d n = a.cross(b).normalized();
      const Vector3d on_b = ea0 + r.uniform(0.05, 0.95) * a + r.distance() * n;
      const double tb = r.uniform(0.05, 0.95), len = r.uniform(0.2, 2.0);
      out.push_back({ea0, ea1, on_b - tb * len * b, on_b + (1 - tb) * len * b});
    }
    // Nearly parallel (angle 1e-7 .. 1e-2 rad) with interior closest points at distance d.
    {
      const Vector3d n = r.unit_perpendicular(a);
      const double angle = r.log_uniform(1e-7, 1e-2);
      const Vector3d b = std::cos(angle) * a + std::sin(angle) * n.cross(a);  // a turned about n
      const Vector3d on_b = ea0 + r.uniform(0.2, 0.8) * a + r.distance() * n;
      const double tb = r.uniform(0.2, 0.8), len = r.uniform(0.5, 1.5);
      out.push_back({ea0, ea1, on_b - tb * len * b, on_b + (1 - tb) * len * b});
    }
    // Nearly parallel (angle 1e-7 .. 1e-2 rad), overlapping, at distance d.
    {
      const Vector3d axis = r.unit_perpendicular(a);
      const double angle = r.log_uniform(1e-7, 1e-2);
      const Vector3d b =
          std::cos(angle) * a + std::sin(angle) * axis.cross(a);  // a rotated about axis
      const Vector3d offset = r.distance() * r.unit_perpendicular(a);
      const Vector3d eb0 = ea0 + r.uniform(-0.5, 0.5) * a + offset;
      out.push_back({ea0, ea1, eb0, eb0 + r.uniform(0.3, 1.5) * b});
    }
    // Exactly parallel (same or opposite direction), at distance d.
    if (with_parallel) {
      const Vector3d offset = r.distance() * r.unit_perpendicular(a);
      const Vector3d eb0 = ea0 + r.uniform(-1.0, 1.5) * a + offset;
      out.push_back({ea0, ea1, eb0, eb0 + (i % 2 ? 1.0 : -1.0) * r.uniform(0.3, 1.5) * a});
    }
    // An endpoint of b near the interior of a.
    {
      const Vector3d eb0 = ea0 + r.uniform(0.05, 0.95) * a + r.distance() * r.unit_perpendicular(a);
      out.push_back({ea0, ea1, eb0, eb0 + r.unit()});
    }
    // Generic.
    out.push_back({ea0, ea1, r.point(), r.point()});
  }
  return out;
}

// Absolute tolerance on distances (not squared): the reference and the kernels each carry
// round-off of ~1e-16 on O(1) coordinates; nearly parallel edges below the kParallelSinSq
// threshold use the point-edge fallback, exact to ~1e-8 of the edge length (distance_type.hpp).
constexpr double kDistanceTolerance = 1e-12;
constexpr double kNearlyParallelTolerance = 1e-7;

// ---------------------------------------------------------------------------------------------
TEST(PointEdgeDistance, ClassifiesConstructedCases) {
  const Vector3d e0(0, 0, 0), e1(1, 0, 0);
  EXPECT_EQ(k::point_edge_distance_type(Vector3d(-1, 1, 0), e0, e1), PE::P_E0);
  EXPECT_EQ(k::point_edge_distance_type(Vector3d(2, 1, 0), e0, e1), PE::P_E1);
  EXPECT_EQ(k::point_edge_distance_type(Vector3d(0.5, 1, 0), e0, e1), PE::P_E);
  EXPECT_DOUBLE_EQ(k::point_edge_distance_sq(Vector3d(0.5, 1, 2), e0, e1), 5.0);
  EXPECT_DOUBLE_EQ(k::point_edge_distance_sq(Vector3d(-1, 1, 0), e0, e1), 2.0);
  // On a vertex, on the interior, on a zero-length edge.
  EXPECT_EQ(k::point_edge_distance_type(e0, e0, e1), PE::P_E0);
  EXPECT_EQ(k::point_edge_distance_sq(e1, e0, e1), 0.0);
  EXPECT_EQ(k::point_edge_distance_type(Vector3d(0.5, 0, 0), e0, e1), PE::P_E);
  EXPECT_EQ(k::point_edge_distance_sq(Vector3d(0.5, 0, 0), e0, e1), 0.0);
  EXPECT_EQ(k::point_edge_distance_type(Vector3d(0, 1, 0), e0, e0), PE::P_E0);
  EXPECT_EQ(k::point_edge_distance_sq(Vector3d(0, 1, 0), e0, e0), 1.0);
}

TEST(PointTriangleDistance, ClassifiesConstructedCases) {
  const Vector3d t0(0, 0, 0), t1(1, 0, 0), t2(0, 1, 0);
  const auto type = [&](double x, double y, double z) {
    return k::point_triangle_distance_type(Vector3d(x, y, z), t0, t1, t2);
  };
  EXPECT_EQ(type(0.2, 0.2, 1), PT::P_T);
  EXPECT_EQ(type(0.2, 0.2, -1), PT::P_T);
  EXPECT_EQ(type(-1, -1, 0.5), PT::P_T0);
  EXPECT_EQ(type(2, -0.5, 1), PT::P_T1);
  EXPECT_EQ(type(-0.5, 2, 1), PT::P_T2);
  EXPECT_EQ(type(0.5, -1, 1), PT::P_E0);
  EXPECT_EQ(type(1, 1, 1), PT::P_E1);
  EXPECT_EQ(type(-1, 0.5, 1), PT::P_E2);
  EXPECT_DOUBLE_EQ(k::point_triangle_distance_sq(Vector3d(0.2, 0.2, 3), t0, t1, t2), 9.0);
  EXPECT_DOUBLE_EQ(k::point_triangle_distance_sq(Vector3d(1, 1, 1), t0, t1, t2), 1.5);
  // Exactly on a vertex and on an edge: distance zero, no division by zero.
  EXPECT_EQ(type(0, 0, 0), PT::P_T0);
  EXPECT_EQ(k::point_triangle_distance_sq(t0, t0, t1, t2), 0.0);
  EXPECT_EQ(type(0.5, 0, 0), PT::P_E0);
  EXPECT_EQ(k::point_triangle_distance_sq(Vector3d(0.5, 0, 0), t0, t1, t2), 0.0);
  // Degenerate triangles have no normal: the nearest edge decides.
  const Vector3d c2(2, 0, 0);
  EXPECT_EQ(k::point_triangle_distance_type(Vector3d(0.5, 1, 0), t0, t1, c2), PT::P_E0);
  EXPECT_EQ(k::point_triangle_distance_type(Vector3d(1.5, 1, 0), t0, t1, c2), PT::P_E1);
  EXPECT_DOUBLE_EQ(k::point_triangle_distance_sq(Vector3d(1.5, 1, 0), t0, t1, c2), 1.0);
  EXPECT_EQ(k::point_triangle_distance_type(Vector3d(0.5, 0, 1), t0, t1, t1), PT::P_E0);
  EXPECT_EQ(k::point_triangle_distance_type(Vector3d(0, 0, 1), t0, t0, t0), PT::P_T0);
}

TEST(EdgeEdgeDistance, ClassifiesConstructedCases) {
  const Vector3d a0(0, 0, 0), a1(1, 0, 0);
  const auto type = [&](const Vector3d& b0, const Vector3d& b1) {
    return k::edge_edge_distance_type(a0, a1, b0, b1);
  };
  EXPECT_EQ(type(Vector3d(0.5, -1, 1), Vector3d(0.5, 1, 1)), EE::EA_EB);
  EXPECT_DOUBLE_EQ(k::edge_edge_distance_sq(a0, a1, Vector3d(0.5, -1, 1), Vector3d(0.5, 1, 1)),
                   1.0);
  EXPECT_EQ(type(Vector3d(2, -1, 1), Vector3d(2, 1, 1)), EE::EA1_EB);
  EXPECT_EQ(type(Vector3d(-2, -1, 1), Vector3d(-2, 1, 1)), EE::EA0_EB);
  EXPECT_EQ(type(Vector3d(0.5, 1, 1), Vector3d(0.5, 2, 1)), EE::EA_EB0);
  EXPECT_EQ(type(Vector3d(0.5, 2, 1), Vector3d(0.5, 1, 1)), EE::EA_EB1);
  EXPECT_EQ(type(Vector3d(2, 1, 1), Vector3d(2, 2, 1)), EE::EA1_EB0);
  EXPECT_EQ(type(Vector3d(-2, 2, 1), Vector3d(-2, 1, 1)), EE::EA0_EB1);
  // Parallel, overlapping: constant distance along the overlap, reported at an endpoint of b.
  EXPECT_EQ(type(Vector3d(0.2, 0, 1), Vector3d(0.8, 0, 1)), EE::EA_EB0);
  EXPECT_DOUBLE_EQ(k::edge_edge_distance_sq(a0, a1, Vector3d(0.2, 0, 1), Vector3d(0.8, 0, 1)), 1.0);
  // Parallel, disjoint along the line; anti-parallel; collinear and overlapping.
  EXPECT_EQ(type(Vector3d(2, 0, 1), Vector3d(3, 0, 1)), EE::EA1_EB0);
  EXPECT_DOUBLE_EQ(k::edge_edge_distance_sq(a0, a1, Vector3d(2, 0, 1), Vector3d(3, 0, 1)), 2.0);
  EXPECT_EQ(type(Vector3d(3, 0, 1), Vector3d(2, 0, 1)), EE::EA1_EB1);
  EXPECT_EQ(k::edge_edge_distance_sq(a0, a1, Vector3d(0.5, 0, 0), Vector3d(1.5, 0, 0)), 0.0);
  // Crossing exactly.
  EXPECT_EQ(type(Vector3d(0.5, -1, 0), Vector3d(0.5, 1, 0)), EE::EA_EB);
  EXPECT_EQ(k::edge_edge_distance_sq(a0, a1, Vector3d(0.5, -1, 0), Vector3d(0.5, 1, 0)), 0.0);
  // Parallel up to 1e-10 rad: below the threshold, so no line-line division.
  const Vector3d b0(0.3, 0, 1e-3), b1 = b0 + Vector3d(1, 1e-10, 0);
  const EE t = type(b0, b1);
  EXPECT_NE(t, EE::EA_EB);
  EXPECT_NEAR(std::sqrt(k::edge_edge_distance_sq(a0, a1, b0, b1)), 1e-3, 1e-9);
}

// Values match the independent reference; on generic configurations (a unique closest pair,
// clear of face boundaries) the classification matches the reference's minimizing faces.
TEST(PointEdgeDistance, MatchesReference) {
  Random r(1);
  int classified = 0;
  const auto configs = point_edge_configurations(r, 300);
  for (const auto& c : configs) {
    const HullDistance ref = hull_distance_sq({c.p}, {c.e0, c.e1});
    const double d = k::point_edge_distance_sq(c.p, c.e0, c.e1);
    ASSERT_NEAR(std::sqrt(d), std::sqrt(ref.d_sq), kDistanceTolerance);
    if (ref.margin > 1e-6) {
      ++classified;
      EXPECT_EQ(support_of(k::point_edge_distance_type(c.p, c.e0, c.e1)), ref.b_support);
    }
  }
  EXPECT_GT(classified, int(configs.size()) / 2);
}

TEST(PointTriangleDistance, MatchesReference) {
  Random r(2);
  int classified = 0;
  const auto configs = point_triangle_configurations(r, 250);
  for (const auto& c : configs) {
    const HullDistance ref = hull_distance_sq({c.p}, {c.t0, c.t1, c.t2});
    const double d = k::point_triangle_distance_sq(c.p, c.t0, c.t1, c.t2);
    ASSERT_NEAR(std::sqrt(d), std::sqrt(ref.d_sq), kDistanceTolerance);
    if (ref.margin > 1e-6) {
      ++classified;
      EXPECT_EQ(support_of(k::point_triangle_distance_type(c.p, c.t0, c.t1, c.t2)), ref.b_support);
    }
  }
  EXPECT_GT(classified, int(configs.size()) / 2);
  // Degenerate (collinear, repeated-vertex) triangles.
  for (int i = 0; i < 200; ++i) {
    const Vector3d t0 = r.point(), t1 = r.point();
    const Vector3d t2 = i % 2 ? t0 + r.uniform(-2, 2) * (t1 - t0) : t1;
    const Vector3d p = r.point();
    ASSERT_NEAR(std::sqrt(k::point_triangle_distance_sq(p, t0, t1, t2)),
                std::sqrt(hull_distance_sq({p}, {t0, t1, t2}).d_sq), kDistanceTolerance);
  }
}

TEST(EdgeEdgeDistance, MatchesReference) {
  Random r(3);
  int classified = 0, generic = 0;
  const auto configs = edge_edge_configurations(r, 250, true);
  for (const auto& c : configs) {
    const HullDistance ref = hull_distance_sq({c.ea0, c.ea1}, {c.eb0, c.eb1});
    const double d = k::edge_edge_distance_sq(c.ea0, c.ea1, c.eb0, c.eb1);
    const Vector3d a = c.ea1 - c.ea0, b = c.eb1 - c.eb0;
    const double sin_sq = a.cross(b).squaredNorm() / (a.squaredNorm() * b.squaredNorm());
    const bool nearly_parallel = sin_sq < 1e-8;
    ASSERT_NEAR(std::sqrt(d), std::sqrt(ref.d_sq),
                nearly_parallel ? kNearlyParallelTolerance : kDistanceTolerance)
        << "sin^2 " << sin_sq;
    if (!nearly_parallel) {
      ++generic;
      if (ref.margin > 1e-6) {
        ++classified;
        EXPECT_EQ(support_of(k::edge_edge_distance_type(c.ea0, c.ea1, c.eb0, c.eb1)),
                  std::make_pair(ref.a_support, ref.b_support));
      }
    }
  }
  EXPECT_GT(classified, generic / 2);
}

// ---------------------------------------------------------------------------------------------
// Derivatives: for the classified type, the analytic gradient and Hessian of that type's closed
// form against central differences of its value and of its analytic gradient. The finite
// differences use a ladder of steps (finite_difference.hpp), since configurations range over
// nine decades of distance.
constexpr double kGradientTolerance = 1e-6;
constexpr double kHessianTolerance = 1e-6;
constexpr double kFloor = 1e-300;

Vec9 stack(const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  Vec9 x;
  x << a, b, c;
  return x;
}
Vec12 stack(const Vector3d& a, const Vector3d& b, const Vector3d& c, const Vector3d& d) {
  Vec12 x;
  x << a, b, c, d;
  return x;
}
Vector3d v(const auto& x, int i) { return x.template segment<3>(3 * i); }

TEST(PointPointDistance, DerivativesMatchFiniteDifferences) {
  Random r(4);
  for (int i = 0; i < 500; ++i) {
    Eigen::Matrix<double, 6, 1> x;
    const Vector3d p1 = r.point();
    x << p1 + r.distance() * r.unit(), p1;
    const auto f = [](const auto& y) { return k::point_point_distance_sq(v(y, 0), v(y, 1)); };
    const auto g = [](const auto& y) {
      return k::point_point_distance_sq_gradient(v(y, 0), v(y, 1));
    };
    EXPECT_LT(min_fd_gradient_error(x, f, g(x), 1.0, kFloor), kGradientTolerance);
    EXPECT_LT(min_fd_jacobian_error<6>(x, g, k::point_point_distance_sq_hessian(v(x, 0), v(x, 1)),
                                       1.0, kFloor),
              kHessianTolerance);
  }
}

TEST(PointEdgeDistance, DerivativesMatchFiniteDifferences) {
  Random r(5);
  for (const auto& c : point_edge_configurations(r, 400)) {
    const PE type = k::point_edge_distance_type(c.p, c.e0, c.e1);
    const Vec9 x = stack(c.p, c.e0, c.e1);
    const auto f = [&](const Vec9& y) {
      return k::point_edge_distance_sq(v(y, 0), v(y, 1), v(y, 2), type);
    };
    const auto g = [&](const Vec9& y) {
      return k::point_edge_distance_sq_gradient(v(y, 0), v(y, 1), v(y, 2), type);
    };
    const Vec9 grad = k::point_edge_distance_sq_gradient(c.p, c.e0, c.e1);
    EXPECT_LT(min_fd_gradient_error(x, f, grad, 1.0, kFloor), kGradientTolerance)
        << "type " << int(type);
    EXPECT_LT(min_fd_jacobian_error<9>(x, g, k::point_edge_distance_sq_hessian(c.p, c.e0, c.e1),
                                       1.0, kFloor),
              kHessianTolerance)
        << "type " << int(type);
  }
}

TEST(PointTriangleDistance, DerivativesMatchFiniteDifferences) {
  Random r(6);
  int per_type[7] = {};
  for (const auto& c : point_triangle_configurations(r, 300)) {
    const PT type = k::point_triangle_distance_type(c.p, c.t0, c.t1, c.t2);
    ++per_type[int(type)];
    const Vec12 x = stack(c.p, c.t0, c.t1, c.t2);
    const auto f = [&](const Vec12& y) {
      return k::point_triangle_distance_sq(v(y, 0), v(y, 1), v(y, 2), v(y, 3), type);
    };
    const auto g = [&](const Vec12& y) {
      return k::point_triangle_distance_sq_gradient(v(y, 0), v(y, 1), v(y, 2), v(y, 3), type);
    };
    const Vec12 grad = k::point_triangle_distance_sq_gradient(c.p, c.t0, c.t1, c.t2);
    EXPECT_LT(min_fd_gradient_error(x, f, grad, 1.0, kFloor), kGradientTolerance)
        << "type " << int(type);
    EXPECT_LT(min_fd_jacobian_error<12>(
                  x, g, k::point_triangle_distance_sq_hessian(c.p, c.t0, c.t1, c.t2), 1.0, kFloor),
              kHessianTolerance)
        << "type " << int(type);
  }
  for (int t = 0; t < 7; ++t) EXPECT_GT(per_type[t], 10) << "type " << t << " barely exercised";
}

// The line-line closed form's relative error in double precision: terms of size ~d / sin cancel
// into a result of size ~d (1 / sin^2), and the normal's direction, known to ~eps / sin, tilts
// the offset between the lines, of size ~L, against a distance d (L / (d sin)). Finite
// differences in double precision carry the same loss, hence the factor 10.
double line_line_tolerance(const EdgeEdge& c) {
  const Vector3d a = c.ea1 - c.ea0, b = c.eb1 - c.eb0;
  const double sin = std::sqrt(a.cross(b).squaredNorm() / (a.squaredNorm() * b.squaredNorm()));
  const double d = std::sqrt(k::line_line_distance_sq(c.ea0, c.ea1, c.eb0, c.eb1));
  const double length = std::max(a.norm(), b.norm());
  return 1e-6 + 10.0 * std::numeric_limits<double>::epsilon() *
                    (1.0 / (sin * sin) + length / (std::max(d, 1e-300) * sin));
}

// Below sin^2 = 1e-4 the line-line Hessian grows like 1 / sin^2 and its finite differences in
// double precision lose more digits than the closed form does; those cases are checked against
// quadruple precision instead.
bool nearly_parallel(const EdgeEdge& c) {
  const Vector3d a = c.ea1 - c.ea0, b = c.eb1 - c.eb0;
  return a.cross(b).squaredNorm() < 1e-4 * a.squaredNorm() * b.squaredNorm();
}

TEST(EdgeEdgeDistance, DerivativesMatchFiniteDifferences) {
  Random r(7);
  int per_type[9] = {};
  for (const auto& c : edge_edge_configurations(r, 400, true)) {
    const EE type = k::edge_edge_distance_type(c.ea0, c.ea1, c.eb0, c.eb1);
    if (type == EE::EA_EB && nearly_parallel(c)) continue;
    ++per_type[int(type)];
    const Vec12 x = stack(c.ea0, c.ea1, c.eb0, c.eb1);
    const auto f = [&](const Vec12& y) {
      return k::edge_edge_distance_sq(v(y, 0), v(y, 1), v(y, 2), v(y, 3), type);
    };
    const auto g = [&](const Vec12& y) {
      return k::edge_edge_distance_sq_gradient(v(y, 0), v(y, 1), v(y, 2), v(y, 3), type);
    };
    const Vec12 grad = k::edge_edge_distance_sq_gradient(c.ea0, c.ea1, c.eb0, c.eb1);
    const double tolerance = type == EE::EA_EB ? line_line_tolerance(c) : kGradientTolerance;
    EXPECT_LT(min_fd_gradient_error(x, f, grad, 1.0, kFloor), tolerance) << "type " << int(type);
    EXPECT_LT(min_fd_jacobian_error<12>(
                  x, g, k::edge_edge_distance_sq_hessian(c.ea0, c.ea1, c.eb0, c.eb1), 1.0, kFloor),
              std::max(tolerance, kHessianTolerance))
        << "type " << int(type);
  }
  for (int t = 0; t < 9; ++t) EXPECT_GT(per_type[t], 10) << "type " << t << " barely exercised";
}

// Squared line-line distance straight from its definition, in quadruple precision.
#if defined(__SIZEOF_FLOAT128__)
using Quad = __float128;
#else
using Quad = long double;  // IEEE binary128 where __float128 is missing (e.g. aarch64 Linux)
#endif
Quad line_line_distance_sq_quad(const std::array<Quad, 12>& x) {
  Quad a[3], b[3], w[3];
  for (int i = 0; i < 3; ++i) {
    a[i] = x[3 + i] - x[i];
    b[i] = x[9 + i] - x[6 + i];
    w[i] = x[6 + i] - x[i];
  }
  const Quad n[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                     a[0] * b[1] - a[1] * b[0]};
  const Quad g = w[0] * n[0] + w[1] * n[1] + w[2] * n[2];
  return g * g / (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

// Nearly parallel edges (sin^2 from ~1e-15 to 1e-4) whose closest points are interior: the
// analytic derivatives against quadruple-precision central differences of the definition, to the
// accuracy the closed form has in double precision (line_line_tolerance). In the contact energy
// the edge-edge mollifier multiplies them by m ~ 1e3 sin^2, which removes the 1 / sin^2 loss.
TEST(EdgeEdgeDistance, NearlyParallelDerivativesMatchQuadPrecision) {
  Random r(8);
  int checked = 0;
  for (const auto& c : edge_edge_configurations(r, 200, false)) {
    if (!nearly_parallel(c) || k::edge_edge_distance_type(c.ea0, c.ea1, c.eb0, c.eb1) != EE::EA_EB)
      continue;
    ++checked;
    const Vector3d a = c.ea1 - c.ea0, b = c.eb1 - c.eb0;
    const double sin = std::sqrt(a.cross(b).squaredNorm() / (a.squaredNorm() * b.squaredNorm()));
    const double tolerance = line_line_tolerance(c);
    const Vec12 x = stack(c.ea0, c.ea1, c.eb0, c.eb1);
    std::array<Quad, 12> xq;
    for (int i = 0; i < 12; ++i) xq[i] = x[i];
    const auto shifted = [&](int i, Quad hi, int j, Quad hj) {
      std::array<Quad, 12> y = xq;
      y[i] += hi;
      y[j] += hj;
      return line_line_distance_sq_quad(y);
    };
    const Vec12 grad = k::edge_edge_distance_sq_gradient(c.ea0, c.ea1, c.eb0, c.eb1);
    const Eigen::Matrix<double, 12, 12> hess =
        k::edge_edge_distance_sq_hessian(c.ea0, c.ea1, c.eb0, c.eb1);
    double grad_error = std::numeric_limits<double>::infinity();
    double hess_error = grad_error;
    for (int e = 12; e <= 20; e += 2) {
      const Quad h = std::pow(10.0, -e);
      Vec12 fd_grad;
      Eigen::Matrix<double, 12, 12> fd_hess;
      for (int i = 0; i < 12; ++i) {
        fd_grad[i] = double((shifted(i, h, i, 0) - shifted(i, -h, i, 0)) / (2 * h));
        for (int j = 0; j < 12; ++j)
          fd_hess(i, j) = double((shifted(i, h, j, h) - shifted(i, h, j, -h) -
                                  shifted(i, -h, j, h) + shifted(i, -h, j, -h)) /
                                 (4 * h * h));
      }
      grad_error = std::min(grad_error, grip::test::relative_error(grad, fd_grad, kFloor));
      hess_error = std::min(hess_error, grip::test::relative_error(hess, fd_hess, kFloor));
    }
    EXPECT_LT(grad_error, tolerance) << "sin " << sin;
    EXPECT_LT(hess_error, tolerance) << "sin " << sin;
  }
  EXPECT_GT(checked, 50);
}

}  // namespace
