#pragma once
// The data-parallel broad phase: every environment's contact candidates of a batch at once,
// exactly the pairs the CPU engine's find_contact_candidates finds (solver/contact/
// candidates.hpp), in its order, with the same friction, mollifier threshold and near-at-rest
// flag. A vertex's box spans its start and end positions, inflated by half of its
// environment's d_hat; an edge's or face's is the union of its vertices'; two primitives are a
// candidate when their boxes overlap and their bodies may touch.
//
// Sort and sweep, one environment filtering another out: the points and faces of the batch are
// sorted by (environment, their box's lower bound along the environment's sweep axis), and so
// are the edges; each primitive then sweeps forward through the sorted list while the others'
// lower bounds lie below its upper bound, within its environment. A pair is found once, from
// the primitive that comes first. The sweep axis is the one along which the environment's
// vertex boxes spread most. Pairs are counted, the counts scanned into offsets, the pairs
// written, then sorted into the CPU engine's order: per environment point-triangle pairs by
// (vertex, face), then edge-edge pairs by (edge, edge). Sorts and scans are the launcher's
// (the standard library's on the host, Thrust's on a GPU); every comparison is a total order,
// so every launcher gives the same lists.
#include <vector>

#include "solver/kernels/aabb.hpp"
#include "solver/kernels/edge_edge_mollifier.hpp"
#include "solver/kernels/hd.hpp"
#include "solver/parallel/surface_batch.hpp"

namespace grip::solver::parallel {

struct BroadPhaseBuffers {
  SurfaceBuffers surface;
  const double* start = nullptr;  // 3 per vertex
  const double* end = nullptr;    // 3 per vertex
  const double* d_hat = nullptr;  // per environment
  // Work: 6 per box (lower x, y, z, upper x, y, z); per environment its sweep axis; the sorted
  // points and faces (point v as v, face f as vertex_count + f) and edges; per sorted item the
  // pairs it finds, then their offsets (one more entry: the total).
  double *vertex_box = nullptr, *edge_box = nullptr, *face_box = nullptr;
  int* axis = nullptr;
  int* point_face_order = nullptr;  // vertex_count + face_count
  int* edge_order = nullptr;        // edge_count
  int* point_face_found = nullptr;  // vertex_count + face_count + 1
  int* edge_found = nullptr;        // edge_count + 1
};

// The candidates found: per pair its primitives as found (point-triangle pairs first, then
// edge-edge ones, in sweep order), then the sorted pairs as ContactCandidate holds them.
struct CandidateBuffers {
  int* primitive = nullptr;  // 2 per pair found: (vertex, face) or (edge, edge)
  int* order = nullptr;      // per pair, the found pair at that place in the sorted list
  int* vertex = nullptr;     // 4 per pair: (p, t0, t1, t2) or (ea0, ea1, eb0, eb1)
  unsigned char* edge_edge = nullptr;
  unsigned char* near_at_rest = nullptr;
  double* friction = nullptr;
  double* mollifier_eps = nullptr;
  int* environment = nullptr;
  int* environment_begin = nullptr;  // environments + 1 offsets into the pairs
};

struct CandidateCounts {
  int point_triangle = 0, edge_edge = 0;
  int total() const { return point_triangle + edge_edge; }
};

GRIP_HD inline Aabb load_box(const double* b) {
  Aabb box;
  for (int k = 0; k < 3; ++k) {
    box.min[k] = b[k];
    box.max[k] = b[3 + k];
  }
  return box;
}

GRIP_HD inline void store_box(const Aabb& box, double* b) {
  for (int k = 0; k < 3; ++k) {
    b[k] = box.min[k];
    b[3 + k] = box.max[k];
  }
}

GRIP_HD inline double pair_friction(const SurfaceBuffers& s, int body_a, int body_b) {
  const int e = s.body_environment[body_a], first = s.body_begin[e];
  const int n = s.body_begin[e + 1] - first;
  return s.friction[s.friction_begin[e] + (body_a - first) * n + (body_b - first)];
}

// Each vertex's box: its start and end, inflated by half of d_hat (and a hair, as the CPU
// engine's broad phase inflates it).
struct VertexBoxStage {
  BroadPhaseBuffers b;

  GRIP_HD void operator()(int v) const {
    const double d_hat = b.d_hat[b.surface.vertex_environment[v]];
    Aabb box;
    box.expand(Eigen::Vector3d(b.start[3 * v], b.start[3 * v + 1], b.start[3 * v + 2]));
    box.expand(Eigen::Vector3d(b.end[3 * v], b.end[3 * v + 1], b.end[3 * v + 2]));
    box.inflate(0.5 * d_hat * (1.0 + 1e-9));
    store_box(box, b.vertex_box + 6 * v);
  }
};

// Each face's (corners 3) or edge's (corners 2) box: the union of its vertices'.
struct PrimitiveBoxStage {
  BroadPhaseBuffers b;
  const int* primitive = nullptr;
  int corners = 0;
  double* box = nullptr;

  GRIP_HD void operator()(int i) const {
    Aabb u = load_box(b.vertex_box + 6 * primitive[corners * i]);
    for (int c = 1; c < corners; ++c)
      u.expand(load_box(b.vertex_box + 6 * primitive[corners * i + c]));
    store_box(u, box + 6 * i);
  }
};

// Each environment's sweep axis: the one along which its vertex boxes' lower corners deviate
// most from their mean (mean absolute deviation; the lowest such axis on a tie). The spread of
// its whole extent would pick a long object's axis, along which a gripper's many small
// primitives all overlap; the deviation follows where the primitives lie. Sums and differences
// only, so that every launcher (a GPU's fused multiply-adds included) picks the same axis.
struct SweepAxisStage {
  BroadPhaseBuffers b;

  GRIP_HD void operator()(int e) const {
    const int first = b.surface.vertex_begin[e], last = b.surface.vertex_begin[e + 1];
    if (first == last) {
      b.axis[e] = 0;
      return;
    }
    Eigen::Vector3d mean = Eigen::Vector3d::Zero(), deviation = Eigen::Vector3d::Zero();
    for (int v = first; v < last; ++v) mean += load_box(b.vertex_box + 6 * v).min;
    mean /= static_cast<double>(last - first);
    for (int v = first; v < last; ++v) {
      deviation += (load_box(b.vertex_box + 6 * v).min - mean).cwiseAbs();
    }
    int axis = 0;
    for (int k = 1; k < 3; ++k) {
      if (deviation[k] > deviation[axis]) axis = k;
    }
    b.axis[e] = axis;
  }
};

struct IotaStage {
  int* items = nullptr;
  GRIP_HD void operator()(int i) const { items[i] = i; }
};

// The points and faces as sort-and-sweep items: item i < vertex_count is point i, the others
// face i - vertex_count.
GRIP_HD inline int point_face_environment(const BroadPhaseBuffers& b, int item) {
  const int points = b.surface.vertex_count;
  return item < points ? b.surface.vertex_environment[item]
                       : b.surface.face_environment[item - points];
}

GRIP_HD inline const double* point_face_box(const BroadPhaseBuffers& b, int item) {
  const int points = b.surface.vertex_count;
  return item < points ? b.vertex_box + 6 * item : b.face_box + 6 * (item - points);
}

// (environment, lower bound along its sweep axis, item): a total order.
struct PointFaceSweepOrder {
  BroadPhaseBuffers b;

  GRIP_HD bool operator()(int i, int j) const {
    const int ei = point_face_environment(b, i), ej = point_face_environment(b, j);
    if (ei != ej) return ei < ej;
    const double li = point_face_box(b, i)[b.axis[ei]], lj = point_face_box(b, j)[b.axis[ej]];
    if (li != lj) return li < lj;
    return i < j;
  }
};

struct EdgeSweepOrder {
  BroadPhaseBuffers b;

  GRIP_HD bool operator()(int i, int j) const {
    const int ei = b.surface.edge_environment[i], ej = b.surface.edge_environment[j];
    if (ei != ej) return ei < ej;
    const double li = b.edge_box[6 * i + b.axis[ei]], lj = b.edge_box[6 * j + b.axis[ej]];
    if (li != lj) return li < lj;
    return i < j;
  }
};

// Aabb::overlaps on stored boxes.
GRIP_HD inline bool boxes_overlap(const double* a, const double* c) {
  for (int k = 0; k < 3; ++k) {
    if (!(a[k] <= c[3 + k]) || !(c[k] <= a[3 + k])) return false;
  }
  return true;
}

// Whether point v and face f are a candidate, their boxes overlapping.
GRIP_HD inline bool point_triangle_allowed(const SurfaceBuffers& s, int v, int f) {
  const int* t = s.face + 3 * f;
  if (t[0] == v || t[1] == v || t[2] == v) return false;
  return pair_friction(s, s.vertex_body[v], s.vertex_body[t[0]]) >= 0.0;
}

// Whether edges a and b are a candidate, their boxes overlapping.
GRIP_HD inline bool edge_edge_allowed(const SurfaceBuffers& s, int a, int c) {
  const int* ea = s.edge + 2 * a;
  const int* ec = s.edge + 2 * c;
  if (ea[0] == ec[0] || ea[0] == ec[1] || ea[1] == ec[0] || ea[1] == ec[1]) return false;
  return pair_friction(s, s.vertex_body[ea[0]], s.vertex_body[ec[0]]) >= 0.0;
}

// One sorted point or face's sweep: counts its pairs (found = null) or writes them from
// found[k] on.
struct PointFaceSweepStage {
  BroadPhaseBuffers b;
  int* primitive = nullptr;  // null: count

  GRIP_HD void operator()(int k) const {
    const int items = b.surface.vertex_count + b.surface.face_count;
    const int points = b.surface.vertex_count;
    const int i = b.point_face_order[k], e = point_face_environment(b, i), axis = b.axis[e];
    const double* box = point_face_box(b, i);
    int n = 0;
    for (int m = k + 1; m < items; ++m) {
      const int j = b.point_face_order[m];
      if (point_face_environment(b, j) != e) break;
      const double* other = point_face_box(b, j);
      if (other[axis] > box[3 + axis]) break;
      if ((i < points) == (j < points)) continue;
      const int v = i < points ? i : j, f = (i < points ? j : i) - points;
      if (!boxes_overlap(b.vertex_box + 6 * v, b.face_box + 6 * f)) continue;
      if (!point_triangle_allowed(b.surface, v, f)) continue;
      if (primitive != nullptr) {
        const int p = b.point_face_found[k] + n;
        primitive[2 * p] = v;
        primitive[2 * p + 1] = f;
      }
      ++n;
    }
    if (primitive == nullptr) b.point_face_found[k] = n;
  }
};

// One sorted edge's sweep. A pair is listed from its edge among untouching bodies, else from
// its lower-numbered edge (as the CPU engine lists it).
struct EdgeSweepStage {
  BroadPhaseBuffers b;
  int first_pair = 0;        // the edge-edge pairs' first place among the pairs found
  int* primitive = nullptr;  // null: count

  GRIP_HD void operator()(int k) const {
    const SurfaceBuffers& s = b.surface;
    const int i = b.edge_order[k], e = s.edge_environment[i], axis = b.axis[e];
    const double* box = b.edge_box + 6 * i;
    int n = 0;
    for (int m = k + 1; m < s.edge_count; ++m) {
      const int j = b.edge_order[m];
      if (s.edge_environment[j] != e) break;
      const double* other = b.edge_box + 6 * j;
      if (other[axis] > box[3 + axis]) break;
      if (!boxes_overlap(box, other) || !edge_edge_allowed(s, i, j)) continue;
      if (primitive != nullptr) {
        const bool ui = s.untouching[s.vertex_body[s.edge[2 * i]]] != 0;
        const bool uj = s.untouching[s.vertex_body[s.edge[2 * j]]] != 0;
        const bool i_first = ui == uj ? i < j : ui;
        const int p = first_pair + b.edge_found[k] + n;
        primitive[2 * p] = i_first ? i : j;
        primitive[2 * p + 1] = i_first ? j : i;
      }
      ++n;
    }
    if (primitive == nullptr) b.edge_found[k] = n;
  }
};

// The count past the last item: 0, so that the scan's last entry is the total.
struct TotalSlotStage {
  int* found = nullptr;
  int items = 0;
  GRIP_HD void operator()(int) const { found[items] = 0; }
};

// The found pairs' order: (environment, edge-edge after point-triangle, first primitive,
// second): the CPU engine's.
struct CandidateOrder {
  BroadPhaseBuffers b;
  const int* primitive = nullptr;
  int point_triangle = 0;  // pairs found before the edge-edge ones

  GRIP_HD void key(int p, int* k) const {
    const bool edge_edge = p >= point_triangle;
    const int a = primitive[2 * p];
    k[0] = edge_edge ? b.surface.edge_environment[a] : b.surface.vertex_environment[a];
    k[1] = edge_edge ? 1 : 0;
    k[2] = a;
    k[3] = primitive[2 * p + 1];
  }
  GRIP_HD bool operator()(int p, int q) const {
    int kp[4], kq[4];
    key(p, kp);
    key(q, kq);
    for (int c = 0; c < 4; ++c) {
      if (kp[c] != kq[c]) return kp[c] < kq[c];
    }
    return false;
  }
};

// Whether the sorted 4-tuples [begin, end) of `pairs` hold `pair`.
GRIP_HD inline bool holds_pair(const int* pairs, int begin, int end, const int* pair) {
  const auto below = [&](int t) {  // tuple t < pair, lexicographically
    for (int c = 0; c < 4; ++c) {
      if (pairs[4 * t + c] != pair[c]) return pairs[4 * t + c] < pair[c];
    }
    return false;
  };
  int low = begin, high = end;
  while (low < high) {  // the first tuple not below `pair`
    const int mid = low + (high - low) / 2;
    if (below(mid)) {
      low = mid + 1;
    } else {
      high = mid;
    }
  }
  if (low == end) return false;
  for (int c = 0; c < 4; ++c) {
    if (pairs[4 * low + c] != pair[c]) return false;
  }
  return true;
}

// Each sorted pair as ContactCandidate holds it.
struct CandidateFillStage {
  BroadPhaseBuffers b;
  CandidateBuffers out;
  int point_triangle = 0;

  GRIP_HD void operator()(int k) const {
    const SurfaceBuffers& s = b.surface;
    const int p = out.order[k], a = out.primitive[2 * p], c = out.primitive[2 * p + 1];
    const bool edge_edge = p >= point_triangle;
    int* v = out.vertex + 4 * k;
    if (edge_edge) {
      for (int corner = 0; corner < 2; ++corner) {
        v[corner] = s.edge[2 * a + corner];
        v[2 + corner] = s.edge[2 * c + corner];
      }
    } else {
      v[0] = a;
      for (int corner = 0; corner < 3; ++corner) v[1 + corner] = s.face[3 * c + corner];
    }
    const int e = s.vertex_environment[v[0]], second = edge_edge ? 2 : 1;
    out.environment[k] = e;
    out.edge_edge[k] = edge_edge ? 1 : 0;
    out.friction[k] = pair_friction(s, s.vertex_body[v[0]], s.vertex_body[v[second]]);
    const auto rest = [&](int corner) {
      const double* x = s.rest + 3 * v[corner];
      return Eigen::Vector3d(x[0], x[1], x[2]);
    };
    out.mollifier_eps[k] =
        edge_edge ? kernels::edge_edge_mollifier_threshold(rest(0), rest(1), rest(2), rest(3))
                  : 0.0;
    // Only a body's own pairs can be near at rest, and the lists number its environment's
    // vertices from 0.
    bool near = false;
    if (s.vertex_body[v[0]] == s.vertex_body[v[second]]) {
      const int first = s.vertex_begin[e];
      const int local[4] = {v[0] - first, v[1] - first, v[2] - first, v[3] - first};
      near = edge_edge ? holds_pair(s.edge_edge_rest, s.edge_edge_rest_begin[e],
                                    s.edge_edge_rest_begin[e + 1], local)
                       : holds_pair(s.point_triangle_rest, s.point_triangle_rest_begin[e],
                                    s.point_triangle_rest_begin[e + 1], local);
    }
    out.near_at_rest[k] = near ? 1 : 0;
  }
};

// Each environment's first pair (item environment_count: the total), by binary search.
struct CandidateBeginStage {
  CandidateBuffers out;
  int count = 0;  // pairs

  GRIP_HD void operator()(int e) const {
    int low = 0, high = count;
    while (low < high) {
      const int mid = low + (high - low) / 2;
      if (out.environment[mid] < e) {
        low = mid + 1;
      } else {
        high = mid;
      }
    }
    out.environment_begin[e] = low;
  }
};

// The first half of a broad phase: boxes, sweep axes, the sorts, and each sorted item's pair
// count scanned into offsets; returns how many pairs there are, so that the caller can size
// the candidate buffers.
template <class Launcher>
CandidateCounts count_candidates(Launcher& launch, const BroadPhaseBuffers& b) {
  const SurfaceBuffers& s = b.surface;
  launch(s.vertex_count, VertexBoxStage{b});
  launch(s.face_count, PrimitiveBoxStage{b, s.face, 3, b.face_box});
  launch(s.edge_count, PrimitiveBoxStage{b, s.edge, 2, b.edge_box});
  launch(s.environment_count, SweepAxisStage{b});
  const int items = s.vertex_count + s.face_count;
  launch(items, IotaStage{b.point_face_order});
  launch(s.edge_count, IotaStage{b.edge_order});
  launch.sort(b.point_face_order, items, PointFaceSweepOrder{b});
  launch.sort(b.edge_order, s.edge_count, EdgeSweepOrder{b});
  launch(items, PointFaceSweepStage{b, nullptr});
  launch(s.edge_count, EdgeSweepStage{b, 0, nullptr});
  launch(1, TotalSlotStage{b.point_face_found, items});
  launch(1, TotalSlotStage{b.edge_found, s.edge_count});
  launch.exclusive_scan(b.point_face_found, items + 1);
  launch.exclusive_scan(b.edge_found, s.edge_count + 1);
  return {launch.fetch(b.point_face_found + items), launch.fetch(b.edge_found + s.edge_count)};
}

// The second half: the pairs written, sorted into the CPU engine's order and filled in. `out`
// holds counts.total() pairs.
template <class Launcher>
void write_candidates(Launcher& launch, const BroadPhaseBuffers& b, const CandidateCounts& counts,
                      const CandidateBuffers& out) {
  const SurfaceBuffers& s = b.surface;
  launch(s.vertex_count + s.face_count, PointFaceSweepStage{b, out.primitive});
  launch(s.edge_count, EdgeSweepStage{b, counts.point_triangle, out.primitive});
  launch(counts.total(), IotaStage{out.order});
  launch.sort(out.order, counts.total(), CandidateOrder{b, out.primitive, counts.point_triangle});
  launch(counts.total(), CandidateFillStage{b, out, counts.point_triangle});
  launch(s.environment_count + 1, CandidateBeginStage{out, counts.total()});
}

// A broad phase's work and candidate arrays in host memory, for the host launchers (the
// device check mirrors them in device memory). The surfaces must outlive it.
class HostBroadPhase {
 public:
  explicit HostBroadPhase(const SurfaceBatch& surfaces);

  // The candidates of every environment's path start -> end (3 per vertex each), with its own
  // d_hat.
  template <class Launcher>
  void find(Launcher& launch, const std::vector<double>& start, const std::vector<double>& end,
            const std::vector<double>& d_hat) {
    const BroadPhaseBuffers b = buffers(start, end, d_hat);
    const CandidateCounts counts = count_candidates(launch, b);
    write_candidates(launch, b, counts, candidates(counts));
  }

  int count() const { return static_cast<int>(environment_.size()); }
  const std::vector<int>& vertex() const { return vertex_; }
  const std::vector<unsigned char>& edge_edge() const { return edge_edge_; }
  const std::vector<unsigned char>& near_at_rest() const { return near_at_rest_; }
  const std::vector<double>& friction() const { return friction_; }
  const std::vector<double>& mollifier_eps() const { return mollifier_eps_; }
  const std::vector<int>& environment() const { return environment_; }
  const std::vector<int>& environment_begin() const { return environment_begin_; }
  const std::vector<int>& axis() const { return axis_; }

 private:
  BroadPhaseBuffers buffers(const std::vector<double>& start, const std::vector<double>& end,
                            const std::vector<double>& d_hat);
  CandidateBuffers candidates(const CandidateCounts& counts);

  const SurfaceBatch& surfaces_;
  std::vector<double> vertex_box_, edge_box_, face_box_;
  std::vector<int> axis_, point_face_order_, edge_order_, point_face_found_, edge_found_;
  std::vector<int> primitive_, order_, vertex_, environment_, environment_begin_;
  std::vector<unsigned char> edge_edge_, near_at_rest_;
  std::vector<double> friction_, mollifier_eps_;
};

}  // namespace grip::solver::parallel
