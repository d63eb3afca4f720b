#include "solver/parallel/cuda/broad_phase_check.cuh"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "solver/parallel/broad_phase.hpp"
#include "solver/parallel/cuda/cuda_launcher.cuh"
#include "solver/parallel/cuda/relative_difference.cuh"
#include "solver/parallel/friction_lag_stages.hpp"
#include "solver/parallel/launch.hpp"
#include "solver/parallel/reach_stages.hpp"

namespace grip::solver::parallel {
namespace {

constexpr int kCells = 16;       // per sheet side
constexpr double kCell = 0.002;  // m
constexpr double kDHat = 1e-3;   // m
constexpr double kCcdRescaling = 0.1;

struct SheetScene {
  SurfaceBatch surfaces;
  std::vector<double> start, end, d_hat, ccd_rescaling;
};

// One sheet of the environment begun last: body `body`, its corner (x0, y0) at height z(i, j).
template <class Height>
void add_sheet(SurfaceBatch& surfaces, int body, int first, Height&& z,
               std::vector<double>& start) {
  const int n = kCells + 1;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      surfaces.add_vertex(body, i * kCell, j * kCell, 0.0);
      start.insert(start.end(), {i * kCell, j * kCell, z(i, j)});
    }
  }
  const auto id = [&](int i, int j) { return first + j * n + i; };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      if (i < kCells) surfaces.add_edge(id(i, j), id(i + 1, j));
      if (j < kCells) surfaces.add_edge(id(i, j), id(i, j + 1));
      if (i < kCells && j < kCells) {
        surfaces.add_edge(id(i, j), id(i + 1, j + 1));
        surfaces.add_face(id(i, j), id(i + 1, j), id(i + 1, j + 1));
        surfaces.add_face(id(i, j), id(i + 1, j + 1), id(i, j + 1));
      }
    }
  }
}

SheetScene sheet_scene(int environments) {
  SheetScene scene;
  const int sheet_vertices = (kCells + 1) * (kCells + 1);
  for (int e = 0; e < environments; ++e) {
    // Body 0, the lower sheet, is among the untouching bodies: it never touches itself.
    scene.surfaces.begin_environment({-1.0, 0.5, 0.5, 0.3}, {1, 0});
    const double gap = 4e-4 + 1e-3 * ((e * 37) % 11) / 10.0;
    add_sheet(
        scene.surfaces, 0, 0, [](int, int) { return 0.0; }, scene.start);
    add_sheet(
        scene.surfaces, 1, sheet_vertices,
        [&](int i, int j) { return gap + 5e-4 * std::sin(0.7 * i + 0.3 * e) * std::cos(0.5 * j); },
        scene.start);
    scene.surfaces.set_near_at_rest({}, {});
    scene.d_hat.push_back(kDHat);
    scene.ccd_rescaling.push_back(kCcdRescaling);
  }
  scene.end = scene.start;
  for (std::size_t v = 0; 3 * v < scene.end.size(); ++v) {
    const bool upper = (v / sheet_vertices) % 2 == 1;
    if (upper) scene.end[3 * v + 2] -= 3e-4;
  }
  return scene;
}

// The surfaces in device memory.
struct DeviceSurfaces {
  explicit DeviceSurfaces(const SurfaceBatch& s)
      : body_begin(s.body_begin()),
        body_vertex_begin(s.body_vertex_begin()),
        friction_begin(s.friction_begin()),
        body_environment(s.body_environment()),
        vertex_body(s.vertex_body()),
        vertex_environment(s.vertex_environment()),
        vertex_begin(s.vertex_begin()),
        edge(s.edge()),
        edge_environment(s.edge_environment()),
        face(s.face()),
        face_environment(s.face_environment()),
        point_triangle_rest_begin(s.point_triangle_rest_begin()),
        point_triangle_rest(s.point_triangle_rest()),
        edge_edge_rest_begin(s.edge_edge_rest_begin()),
        edge_edge_rest(s.edge_edge_rest()),
        friction(s.friction()),
        rest(s.rest()),
        untouching(s.untouching()) {}

  SurfaceBuffers buffers(const SurfaceBuffers& host) const {
    SurfaceBuffers d = host;  // the counts
    d.body_begin = body_begin.data();
    d.body_vertex_begin = body_vertex_begin.data();
    d.friction_begin = friction_begin.data();
    d.friction = friction.data();
    d.body_environment = body_environment.data();
    d.untouching = untouching.data();
    d.vertex_body = vertex_body.data();
    d.vertex_environment = vertex_environment.data();
    d.vertex_begin = vertex_begin.data();
    d.rest = rest.data();
    d.edge = edge.data();
    d.edge_environment = edge_environment.data();
    d.face = face.data();
    d.face_environment = face_environment.data();
    d.point_triangle_rest_begin = point_triangle_rest_begin.data();
    d.point_triangle_rest = point_triangle_rest.data();
    d.edge_edge_rest_begin = edge_edge_rest_begin.data();
    d.edge_edge_rest = edge_edge_rest.data();
    return d;
  }

  DeviceArray<int> body_begin, body_vertex_begin, friction_begin, body_environment, vertex_body,
      vertex_environment, vertex_begin, edge, edge_environment, face, face_environment,
      point_triangle_rest_begin, point_triangle_rest, edge_edge_rest_begin, edge_edge_rest;
  DeviceArray<double> friction, rest;
  DeviceArray<char> untouching;
};

// The candidates' arrays in device memory, for `pairs` pairs and `environments`.
struct DeviceCandidates {
  DeviceCandidates(int pairs, int environments)
      : primitive(2 * std::size_t(pairs)),
        order(pairs),
        vertex(4 * std::size_t(pairs)),
        environment(pairs),
        environment_begin(environments + 1),
        edge_edge(pairs),
        near_at_rest(pairs),
        friction(pairs),
        mollifier_eps(pairs) {}

  CandidateBuffers buffers() {
    return {primitive.data(),     order.data(),        vertex.data(),
            edge_edge.data(),     near_at_rest.data(), friction.data(),
            mollifier_eps.data(), environment.data(),  environment_begin.data()};
  }

  DeviceArray<int> primitive, order, vertex, environment, environment_begin;
  DeviceArray<unsigned char> edge_edge, near_at_rest;
  DeviceArray<double> friction, mollifier_eps;
};

// The first n entries of a device list against the host's.
bool same_prefix(const DeviceArray<int>& device, const std::vector<int>& host, int n) {
  const std::vector<int> copy = device.to_host();
  return std::equal(copy.begin(), copy.begin() + n, host.begin());
}

// The first of the device's candidate arrays that differs from the host's ("" when none):
// integers and mu exactly, the mollifier thresholds (computed) to round-off.
std::string candidate_mismatch(DeviceCandidates& d, const HostBroadPhase& host) {
  if (d.vertex.to_host() != host.vertex()) return "vertex";
  if (d.edge_edge.to_host() != host.edge_edge()) return "edge_edge";
  if (d.near_at_rest.to_host() != host.near_at_rest()) return "near_at_rest";
  if (d.friction.to_host() != host.friction()) return "friction";
  if (d.environment.to_host() != host.environment()) return "environment";
  if (d.environment_begin.to_host() != host.environment_begin()) return "environment_begin";
  if (relative_difference(d.mollifier_eps.to_host(), host.mollifier_eps(), 1) > 1e-12) {
    return "mollifier_eps";
  }
  return "";
}

// The reach filter's lists on the device against the host's ("" when equal).
std::string reach_mismatch(const ReachStorage<DeviceArray>& device, int reachable, int watched,
                           const ReachStorage<HostArray>& host, const BroadPhaseCheck& check) {
  if (reachable != check.reachable) return "within-reach count";
  if (watched != check.watched) return "watched count";
  if (!same_prefix(device.reachable, host.reachable, reachable)) return "reachable";
  if (!same_prefix(device.ccd, host.ccd, watched)) return "ccd";
  if (device.reachable_begin.to_host() != host.reachable_begin) return "reachable_begin";
  if (device.ccd_begin.to_host() != host.ccd_begin) return "ccd_begin";
  return "";
}

// The host launcher's candidates and lists, timed.
void run_on_host(const SheetScene& scene, HostBroadPhase& host, ReachStorage<HostArray>& reach,
                 BroadPhaseCheck& check) {
  const SurfaceBuffers s = scene.surfaces.buffers();
  SerialLauncher serial;
  const auto begin = std::chrono::steady_clock::now();
  host.find(serial, scene.start, scene.end, scene.d_hat);
  reach = ReachStorage<HostArray>(s, host.count());
  find_within_reach(serial,
                    reach.buffers(s, scene.start.data(), scene.end.data(), scene.d_hat.data(),
                                  scene.ccd_rescaling.data(), host.count(), host.vertex().data(),
                                  host.edge_edge().data(), host.environment().data(),
                                  host.environment_begin().data()),
                    check.reachable, check.watched);
  check.host_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin).count();
  check.pairs = host.count();
}

template <class T>
std::vector<T> host_copy(const std::vector<T>& v) {
  return v;
}
template <class T>
std::vector<T> host_copy(const DeviceArray<T>& v) {
  return v.to_host();
}

// The candidates as the friction lag reads them (arrays in the launcher's memory).
struct LagInputs {
  int count = 0, environments = 0;
  const int* vertex = nullptr;
  const unsigned char* edge_edge = nullptr;
  const unsigned char* near_at_rest = nullptr;
  const double* friction = nullptr;
  const double* mollifier_eps = nullptr;
  const int* environment = nullptr;
  const int* environment_begin = nullptr;
  const double* positions = nullptr;
  const double* d_hat = nullptr;
  const double* kappa = nullptr;
};

struct LagResult {
  std::vector<int> vertex, environment, contact_begin;
  std::vector<double> mu_lambda, tangent;
};

template <template <class> class Array, class Launcher>
LagResult friction_lag(Launcher& launch, const LagInputs& in) {
  Array<int> keep(std::size_t(in.count) + 1);
  Array<double> mu_lambda(in.count), tangent(24 * std::size_t(in.count));
  const FrictionLagBuffers b{
      in.count,        in.vertex,        in.edge_edge,     in.near_at_rest,
      in.friction,     in.mollifier_eps, in.environment,   in.environment_begin,
      in.environments, in.positions,     in.d_hat,         in.kappa,
      false,           keep.data(),      mu_lambda.data(), tangent.data()};
  const int total = count_lagged_contacts(launch, b);
  Array<int> vertex(4 * std::size_t(total)), environment(total), begin(in.environments + 1);
  Array<double> out_mu_lambda(total), out_tangent(24 * std::size_t(total));
  write_lagged_contacts(
      launch, b,
      {vertex.data(), out_tangent.data(), out_mu_lambda.data(), environment.data(), begin.data()});
  return {host_copy(vertex), host_copy(environment), host_copy(begin), host_copy(out_mu_lambda),
          host_copy(out_tangent)};
}

// Per contact T T^T (12 x 12) of its tangent operator T (12 x 2, by column): what friction
// depends on. T itself is not compared: where the closest features tie (grid-aligned sheets), a
// round-off picks the contact type, whose tangent basis is the other's turned in the same plane.
std::vector<double> tangent_projectors(const std::vector<double>& tangent) {
  std::vector<double> projector(tangent.size() / 24 * 144);
  for (std::size_t c = 0; 24 * c < tangent.size(); ++c) {
    const Eigen::Map<const Eigen::Matrix<double, 12, 2>> t(tangent.data() + 24 * c);
    Eigen::Map<Eigen::Matrix<double, 12, 12>>(projector.data() + 144 * c) = t * t.transpose();
  }
  return projector;
}

// The friction lag over the candidates, the upper sheets raised 0.5 mm off their start (whose
// ripples reach below the lower sheet where the gap is smallest): 0.4 to 2.4 mm apart.
void check_friction_lag(const SheetScene& scene, const HostBroadPhase& host,
                        DeviceCandidates& found, BroadPhaseCheck& check) {
  const int environments = static_cast<int>(scene.d_hat.size());
  const std::vector<double> kappa(environments, 1e3);
  std::vector<double> positions = scene.start;
  const std::size_t sheet_vertices = (kCells + 1) * (kCells + 1);
  for (std::size_t v = 0; 3 * v < positions.size(); ++v) {
    if ((v / sheet_vertices) % 2 == 1) positions[3 * v + 2] += 5e-4;
  }
  SerialLauncher serial;
  const LagResult on_host = friction_lag<HostArray>(
      serial, {host.count(), environments, host.vertex().data(), host.edge_edge().data(),
               host.near_at_rest().data(), host.friction().data(), host.mollifier_eps().data(),
               host.environment().data(), host.environment_begin().data(), positions.data(),
               scene.d_hat.data(), kappa.data()});
  const DeviceArray<double> device_positions(positions), d_hat(scene.d_hat), device_kappa(kappa);
  CudaLauncher launch;
  const LagResult on_device = friction_lag<DeviceArray>(
      launch, {host.count(), environments, found.vertex.data(), found.edge_edge.data(),
               found.near_at_rest.data(), found.friction.data(), found.mollifier_eps.data(),
               found.environment.data(), found.environment_begin.data(), device_positions.data(),
               d_hat.data(), device_kappa.data()});
  check.lagged = static_cast<int>(on_host.environment.size());
  check.lag_identical = on_device.vertex == on_host.vertex &&
                        on_device.environment == on_host.environment &&
                        on_device.contact_begin == on_host.contact_begin;
  check.lag_difference = std::max(relative_difference(on_device.mu_lambda, on_host.mu_lambda, 1),
                                  relative_difference(tangent_projectors(on_device.tangent),
                                                      tangent_projectors(on_host.tangent), 144));
}

// The broad phase's work arrays in device memory, as HostBroadPhase holds them on the host.
struct DeviceSweepWork {
  explicit DeviceSweepWork(const SurfaceBuffers& s)
      : vertex_box(6 * std::size_t(s.vertex_count)),
        edge_box(6 * std::size_t(s.edge_count)),
        face_box(6 * std::size_t(s.face_count)),
        axis(s.environment_count),
        point_face_order(std::size_t(s.vertex_count + s.face_count)),
        edge_order(s.edge_count),
        point_face_found(point_face_order.size() + 1),
        edge_found(edge_order.size() + 1),
        body_point_begin(std::size_t(s.body_count) + 1),
        body_face_begin(body_point_begin.size()),
        body_edge_begin(body_point_begin.size()) {}

  BroadPhaseBuffers buffers(const SurfaceBuffers& on_device, const double* start, const double* end,
                            const double* d_hat) {
    // Designated, so that an order other than BroadPhaseBuffers' own does not compile.
    return {.surface = on_device,
            .start = start,
            .end = end,
            .d_hat = d_hat,
            .vertex_box = vertex_box.data(),
            .edge_box = edge_box.data(),
            .face_box = face_box.data(),
            .axis = axis.data(),
            .point_face_order = point_face_order.data(),
            .edge_order = edge_order.data(),
            .body_point_begin = body_point_begin.data(),
            .body_face_begin = body_face_begin.data(),
            .body_edge_begin = body_edge_begin.data(),
            .point_face_found = point_face_found.data(),
            .edge_found = edge_found.data()};
  }

  DeviceArray<double> vertex_box, edge_box, face_box;
  DeviceArray<int> axis, point_face_order, edge_order, point_face_found, edge_found,
      body_point_begin, body_face_begin, body_edge_begin;
};

}  // namespace

BroadPhaseCheck check_broad_phase(int environments, int repeats) {
  const SheetScene scene = sheet_scene(environments);
  const SurfaceBuffers s = scene.surfaces.buffers();
  BroadPhaseCheck check;
  HostBroadPhase host(scene.surfaces);
  ReachStorage<HostArray> host_reach(s, 0);
  run_on_host(scene, host, host_reach, check);

  const DeviceSurfaces surfaces(scene.surfaces);
  DeviceArray<double> start(scene.start), end(scene.end), d_hat(scene.d_hat),
      rescaling(scene.ccd_rescaling);
  DeviceSweepWork work(s);
  const SurfaceBuffers on_device = surfaces.buffers(s);
  const BroadPhaseBuffers b = work.buffers(on_device, start.data(), end.data(), d_hat.data());
  CudaLauncher launch;
  const CandidateCounts counts = count_candidates(launch, b);
  DeviceCandidates found(counts.total(), environments);
  ReachStorage<DeviceArray> device_reach(s, counts.total());
  const ReachBuffers reach =
      device_reach.buffers(on_device, start.data(), end.data(), d_hat.data(), rescaling.data(),
                           counts.total(), found.vertex.data(), found.edge_edge.data(),
                           found.environment.data(), found.environment_begin.data());
  int reachable = 0, watched = 0;
  check.device_ms = device_median_ms(repeats, [&] {
    count_candidates(launch, b);
    write_candidates(launch, b, counts, found.buffers());
    find_within_reach(launch, reach, reachable, watched);
  });
  check.mismatch =
      counts.total() != host.count() ? "candidate count" : candidate_mismatch(found, host);
  if (check.mismatch.empty()) {
    check.mismatch = reach_mismatch(device_reach, reachable, watched, host_reach, check);
  }
  check.identical = check.mismatch.empty();
  check_friction_lag(scene, host, found, check);
  const std::size_t items = std::size_t(s.vertex_count + s.face_count);
  check.bytes =
      8.0 * double(start.size() + end.size() + work.vertex_box.size() + work.edge_box.size() +
                   work.face_box.size() + surfaces.rest.size() + found.friction.size() +
                   found.mollifier_eps.size() + 2 * std::size_t(s.vertex_count)) +
      4.0 * double(items * 3 + 3 * std::size_t(s.edge_count) + 3 * (std::size_t(s.body_count) + 1) +
                   found.primitive.size() + found.order.size() + found.vertex.size() +
                   found.environment.size() + surfaces.edge.size() + surfaces.face.size() +
                   surfaces.vertex_body.size() + 4 * std::size_t(counts.total()));
  return check;
}

}  // namespace grip::solver::parallel
