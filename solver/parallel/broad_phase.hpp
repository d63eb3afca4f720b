#pragma once
// The data-parallel broad phase: every environment's contact candidates of a batch at once,
// exactly the pairs the CPU engine's find_contact_candidates finds (solver/contact/
// candidates.hpp), in its order, with the same friction, mollifier threshold and near-at-rest
// flag. A vertex's box spans its start and end positions, inflated by half of its
// environment's d_hat; an edge's or face's is the union of its vertices'; two primitives are a
// candidate when their boxes overlap and their bodies may touch.
//
// Sort and sweep per pair of bodies that may touch: the points, the faces and the edges of the
// batch are each sorted by (body, their box's lower bound along their environment's sweep axis);
// each primitive then sweeps, for every body of its environment that its own may touch (itself
// included only where a body touches itself), through that body's part of the list it pairs
// with, from where their lower bounds reach its own (a binary search) while they lie below its
// upper bound. A pair is found once, from the primitive whose lower bound comes first. So a
// hand's links, which never touch each other, sweep only the object, and a rigid body never
// sweeps its own primitives. The sweep axis is the one along which the environment's vertex
// boxes spread most. Pairs are counted, the counts scanned into offsets, the pairs written,
// then sorted into the CPU engine's order: per environment point-triangle pairs by (vertex,
// face), then edge-edge pairs by (edge, edge). Sorts and scans are the launcher's (the standard
// library's on the host, Thrust's on a GPU); every comparison is a total order, so every
// launcher gives the same lists.
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
  int* point_face_order = nullptr;  // vertex_count + face_count: the points', then the faces'
  int* edge_order = nullptr;        // edge_count
  // Per body (one more entry: the list's length) its first place in the sorted points, faces
  // (counted from the faces' first) and edges.
  int *body_point_begin = nullptr, *body_face_begin = nullptr, *body_edge_begin = nullptr;
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

// The three sorted lists: points (vertices), faces and edges, each by (body, lower bound along
// its environment's sweep axis, index). Bodies are numbered across the batch in environment
// order, so that each environment's items, and within it each body's, lie together.
enum SweepList : int { kSweepPoints = 0, kSweepFaces = 1, kSweepEdges = 2 };

GRIP_HD inline int item_body(const BroadPhaseBuffers& b, int list, int item) {
  const SurfaceBuffers& s = b.surface;
  if (list == kSweepPoints) return s.vertex_body[item];
  return s.vertex_body[list == kSweepFaces ? s.face[3 * item] : s.edge[2 * item]];
}

GRIP_HD inline const double* item_box(const BroadPhaseBuffers& b, int list, int item) {
  if (list == kSweepPoints) return b.vertex_box + 6 * item;
  return list == kSweepFaces ? b.face_box + 6 * item : b.edge_box + 6 * item;
}

// The item's lower bound along its environment's sweep axis.
GRIP_HD inline double item_lower(const BroadPhaseBuffers& b, int list, int item) {
  const int body = item_body(b, list, item);
  return item_box(b, list, item)[b.axis[b.surface.body_environment[body]]];
}

// (body, lower bound, index): a total order.
struct SweepOrder {
  BroadPhaseBuffers b;
  int list = kSweepPoints;

  GRIP_HD bool operator()(int i, int j) const {
    const int bi = item_body(b, list, i), bj = item_body(b, list, j);
    if (bi != bj) return bi < bj;
    const double li = item_lower(b, list, i), lj = item_lower(b, list, j);
    if (li != lj) return li < lj;
    return i < j;
  }
};

// Each body's first place in a sorted list (item body_count: the list's length), by binary
// search.
struct SweepBodyBeginStage {
  BroadPhaseBuffers b;
  int list = kSweepPoints;
  const int* sorted = nullptr;
  int count = 0;  // items in the list
  int* begin = nullptr;

  GRIP_HD void operator()(int body) const {
    int low = 0, high = count;
    while (low < high) {
      const int mid = low + (high - low) / 2;
      if (item_body(b, list, sorted[mid]) < body) {
        low = mid + 1;
      } else {
        high = mid;
      }
    }
    begin[body] = low;
  }
};

// The first place m in sorted[begin, end) (one body's items) from which the items' lower bounds
// are no longer `below` the sweeping item's: where its sweep through that body starts.
template <class Below>
GRIP_HD int sweep_start(const int* sorted, int begin, int end, const Below& below) {
  while (begin < end) {
    const int mid = begin + (end - begin) / 2;
    if (below(sorted[mid])) {
      begin = mid + 1;
    } else {
      end = mid;
    }
  }
  return begin;
}

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

// One sorted point's (k below the vertex count) or face's sweep: counts its pairs (primitive =
// null) or writes them from point_face_found[k] on. It visits only the faces (or points) of the
// bodies its own may touch, each body's from where their lower bounds reach its own: a point
// finds the faces whose lower bound is not below its own, a face the points whose lower bound
// is above its own, so that each pair of overlapping boxes is found once.
struct PointFaceSweepStage {
  BroadPhaseBuffers b;
  int* primitive = nullptr;  // null: count

  GRIP_HD void operator()(int k) const {
    const SurfaceBuffers& s = b.surface;
    const bool point = k < s.vertex_count;
    const int list = point ? kSweepPoints : kSweepFaces,
              other_list = point ? kSweepFaces : kSweepPoints;
    const int* sorted = b.point_face_order + (point ? 0 : s.vertex_count);
    const int* others = b.point_face_order + (point ? s.vertex_count : 0);
    const int* other_begin = point ? b.body_face_begin : b.body_point_begin;
    const int i = sorted[point ? k : k - s.vertex_count], body = item_body(b, list, i);
    const int e = s.body_environment[body], axis = b.axis[e];
    const double* box = item_box(b, list, i);
    int n = 0;
    for (int other = s.body_begin[e]; other < s.body_begin[e + 1]; ++other) {
      if (pair_friction(s, point ? body : other, point ? other : body) < 0.0) continue;
      const auto below = [&](int j) {
        const double lower = item_box(b, other_list, j)[axis];
        return point ? lower < box[axis] : lower <= box[axis];
      };
      const int end = other_begin[other + 1];
      for (int m = sweep_start(others, other_begin[other], end, below); m < end; ++m) {
        const int j = others[m];
        const double* other_box = item_box(b, other_list, j);
        if (other_box[axis] > box[3 + axis]) break;
        const int v = point ? i : j, f = point ? j : i;
        if (!boxes_overlap(box, other_box) || !point_triangle_allowed(s, v, f)) continue;
        if (primitive != nullptr) {
          const int p = b.point_face_found[k] + n;
          primitive[2 * p] = v;
          primitive[2 * p + 1] = f;
        }
        ++n;
      }
    }
    if (primitive == nullptr) b.point_face_found[k] = n;
  }
};

// One sorted edge's sweep, through the edges of each body its own may touch from where their
// (lower bound, index) comes after its own. A pair is listed from its edge among untouching
// bodies, else from its lower-numbered edge (as the CPU engine lists it).
struct EdgeSweepStage {
  BroadPhaseBuffers b;
  int first_pair = 0;        // the edge-edge pairs' first place among the pairs found
  int* primitive = nullptr;  // null: count

  GRIP_HD void operator()(int k) const {
    const SurfaceBuffers& s = b.surface;
    const int i = b.edge_order[k], body = item_body(b, kSweepEdges, i);
    const int e = s.body_environment[body], axis = b.axis[e];
    const double* box = b.edge_box + 6 * i;
    const auto below = [&](int j) {
      const double lower = b.edge_box[6 * j + axis];
      return lower < box[axis] || (lower == box[axis] && j <= i);
    };
    int n = 0;
    for (int other = s.body_begin[e]; other < s.body_begin[e + 1]; ++other) {
      if (pair_friction(s, body, other) < 0.0) continue;
      const int end = b.body_edge_begin[other + 1];
      for (int m = sweep_start(b.edge_order, b.body_edge_begin[other], end, below); m < end; ++m) {
        const int j = b.edge_order[m];
        const double* other_box = b.edge_box + 6 * j;
        if (other_box[axis] > box[3 + axis]) break;
        if (!boxes_overlap(box, other_box) || !edge_edge_allowed(s, i, j)) continue;
        if (primitive != nullptr) {
          const bool ui = s.untouching[body] != 0;
          const bool uj = s.untouching[other] != 0;
          const bool i_first = ui == uj ? i < j : ui;
          const int p = first_pair + b.edge_found[k] + n;
          primitive[2 * p] = i_first ? i : j;
          primitive[2 * p + 1] = i_first ? j : i;
        }
        ++n;
      }
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
  int* faces = b.point_face_order + s.vertex_count;
  launch(s.vertex_count, IotaStage{b.point_face_order});
  launch(s.face_count, IotaStage{faces});
  launch(s.edge_count, IotaStage{b.edge_order});
  launch.sort(b.point_face_order, s.vertex_count, SweepOrder{b, kSweepPoints});
  launch.sort(faces, s.face_count, SweepOrder{b, kSweepFaces});
  launch.sort(b.edge_order, s.edge_count, SweepOrder{b, kSweepEdges});
  const int bodies = s.body_count + 1;
  launch(bodies, SweepBodyBeginStage{b, kSweepPoints, b.point_face_order, s.vertex_count,
                                     b.body_point_begin});
  launch(bodies, SweepBodyBeginStage{b, kSweepFaces, faces, s.face_count, b.body_face_begin});
  launch(bodies,
         SweepBodyBeginStage{b, kSweepEdges, b.edge_order, s.edge_count, b.body_edge_begin});
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
  std::vector<int> body_point_begin_, body_face_begin_, body_edge_begin_;
  std::vector<int> primitive_, order_, vertex_, environment_, environment_begin_;
  std::vector<unsigned char> edge_edge_, near_at_rest_;
  std::vector<double> friction_, mollifier_eps_;
};

}  // namespace grip::solver::parallel
