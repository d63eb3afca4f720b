#pragma once
// One continuous-collision query of the CCD benchmark: the 4 vertices of a vertex-face or
// edge-edge pair at t = 0 and at t = 1 (linear motion between), and whether they collide
// (touching at t = 0 included).
#include <gmpxx.h>
#include <Eigen/Core>
#include <array>
#include <cstddef>

namespace grip::bench {

// vf: rows are p, t0, t1, t2 at t = 0, then the same at t = 1.
// ee: rows are ea0, ea1, eb0, eb1 at t = 0, then the same at t = 1.
enum class CcdQueryType { kVertexFace, kEdgeEdge };

inline constexpr std::size_t kCcdQueryRows = 8;

// A query in double precision, as a simulator would pose it (coordinates rounded to nearest).
struct CcdQuery {
  std::array<Eigen::Vector3d, kCcdQueryRows> vertices;
  bool collides = false;  // ground truth of the exact (rational) query, as labelled
  // The exact (rational) primitives touch at t = 0 (distance 0); set by the file reader.
  bool touches_at_start = false;
};

// The ground truth the benchmark scores against: a touching start is a collision, whatever the
// label says (a conservative CCD must answer t = 0 there).
inline bool collides_in_truth(const CcdQuery& query) {
  return query.collides || query.touches_at_start;
}

// A query with exact rational coordinates, as the benchmark files store it.
struct RationalCcdQuery {
  std::array<std::array<mpq_class, 3>, kCcdQueryRows> vertices;
  bool collides = false;
};

// Each coordinate rounded to the nearest double.
CcdQuery to_double_query(const RationalCcdQuery& query);

}  // namespace grip::bench
