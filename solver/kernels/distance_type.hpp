#pragma once
// Which sub-primitives realize the distance between two closed primitives (the "distance type"),
// and the threshold below which a triangle counts as degenerate or two edges as parallel.

namespace grip::solver::kernels {

// Point to edge (e0, e1): an endpoint or the edge interior.
enum class PointEdgeDistanceType { P_E0, P_E1, P_E };

// Point to triangle (t0, t1, t2): a vertex, an edge (E0 = t0t1, E1 = t1t2, E2 = t2t0) or the
// face interior.
enum class PointTriangleDistanceType { P_T0, P_T1, P_T2, P_E0, P_E1, P_E2, P_T };

// Edge a (ea0, ea1) to edge b (eb0, eb1): endpoint to endpoint, edge interior to endpoint,
// endpoint to edge interior, or interior to interior (the only case using the line-line distance).
enum class EdgeEdgeDistanceType {
  EA0_EB0,
  EA0_EB1,
  EA1_EB0,
  EA1_EB1,
  EA_EB0,
  EA_EB1,
  EA0_EB,
  EA1_EB,
  EA_EB
};

// sin^2 of the angle between two edge vectors below which the face normal (or the common normal
// of two lines) is not used. At sin^2 = machine epsilon the round-off of the normal (~eps / sin)
// and the error of falling back to point-edge distances (~sin) are both ~1e-8 of the edge length.
inline constexpr double kParallelSinSq = 2.220446049250313e-16;

}  // namespace grip::solver::kernels
