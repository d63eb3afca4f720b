// grip-gpu-check: the data-parallel engine's stages on a GPU against the host launcher on the
// same batches (scripts/gpu-check.sh runs it). Batches of 1 to 512 soft-box environments, each
// deformed differently, go through the elastic stages (per-tet energy, gradient and projected
// Hessian; per-vertex gradient gather; per-environment energy; the vertices' inertia target and
// inertia), the barrier stage (512 contact pairs per environment, point-triangle and edge-edge,
// some nearly parallel, at 5 % to 120 % of d_hat), the friction stage (the same pairs as lagged
// friction contacts, sliding 0.1 to 10 times eps_v h), the affine stages (17 affine bodies per
// environment, as a hand's 16 driven links and its object: prediction, inertia, orthogonality,
// drive), the map between DOFs and collision vertices (positions of the box's vertices, the
// affine bodies' corners and 8 scripted vertices; 512 contact pairs' gradients gathered into the
// DOFs, their Hessians assembled in 3x3 blocks), the step bound (additive CCD over the barrier's
// pairs, each closing by up to 2.5 mm, and its per-environment minimum), the linear solve
// (two-level CG on the box's M + h^2 K, its bottom layer pinned), the broad phase (two
// facing sheets per environment, broad_phase_check.cu) and the line search's halving of a random
// Newton step until no tet inverts, and the incremental potential with Armijo's sufficient
// decrease (potential_check.cu) on the device (CudaLauncher) and on one host core
// (SerialLauncher); it reports the largest relative differences, the device's and the host's
// times, CG's iterations, the candidates found, the halvings, and device memory per
// environment, as JSON and Markdown in OUTDIR.
// Exit status: 0 when every difference is within its tolerance, 1 when one is not, 2 when no
// CUDA device is found or OUTDIR cannot be written.
//   grip-gpu-check OUTDIR [--sizes 1,8,64,256,512] [--repeats 5]
#include <cuda_runtime.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "solver/kernels/relative_velocity.hpp"
#include "solver/parallel/affine_batch.hpp"
#include "solver/parallel/affine_stages.hpp"
#include "solver/parallel/block_assembly.hpp"
#include "solver/parallel/block_pcg.hpp"
#include "solver/parallel/ccd_stages.hpp"
#include "solver/parallel/collision_batch.hpp"
#include "solver/parallel/contact_stages.hpp"
#include "solver/parallel/cuda/broad_phase_check.cuh"
#include "solver/parallel/cuda/cuda_launcher.cuh"
#include "solver/parallel/cuda/dense_check.cuh"
#include "solver/parallel/cuda/potential_check.cuh"
#include "solver/parallel/cuda/relative_difference.cuh"
#include "solver/parallel/elastic_stages.hpp"
#include "solver/parallel/fem_batch.hpp"
#include "solver/parallel/friction_stages.hpp"
#include "solver/parallel/inertia_stages.hpp"
#include "solver/parallel/launch.hpp"
#include "solver/parallel/line_search_stages.hpp"
#include "solver/parallel/map_stages.hpp"
#include "solver/parallel/step_start_stages.hpp"

namespace {

using namespace grip::solver::parallel;

// Tolerances, relative to the largest magnitude compared: the device contracts multiply-adds
// (FMA) where the host does not, and the Hessian's projection takes eigenvectors of nearly
// repeated singular values, defined to about 1e-9 (kernels/neo_hookean.hpp).
constexpr double kEnergyTolerance = 1e-10;
constexpr double kGradientTolerance = 1e-10;
constexpr double kHessianTolerance = 1e-7;
// ACCD iterates: round-off that differs can end its advances at other points of the same
// conservative bound.
constexpr double kCcdTolerance = 1e-6;
// CG solutions (to a relative residual of 1e-10) whose iterates round differently: within the
// condition number times that of each other. Their iteration counts within two.
constexpr double kPcgTolerance = 1e-6;
constexpr double kPcgResidual = 1e-10;
constexpr int kPcgIterationSlack = 2;
constexpr int kPcgMaxIterations = 2000;

// A box of nx x ny x nz cubes of edge `cell`, six positively oriented tets per cube.
struct BoxMesh {
  std::vector<double> rest;
  std::vector<int> tets;
};

BoxMesh box_mesh(int nx, int ny, int nz, double cell) {
  BoxMesh mesh;
  const auto id = [&](int i, int j, int k) { return (k * (ny + 1) + j) * (nx + 1) + i; };
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
        mesh.rest.insert(mesh.rest.end(), {i * cell, j * cell, k * cell});
  const int kuhn[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7},
                          {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};
  const auto x = [&](int v, int a) { return mesh.rest[3 * v + a]; };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        int corner[8];
        for (int c = 0; c < 8; ++c) corner[c] = id(i + (c & 1), j + ((c >> 1) & 1), k + (c >> 2));
        for (const auto& t : kuhn) {
          int v[4] = {corner[t[0]], corner[t[1]], corner[t[2]], corner[t[3]]};
          double e[3][3];
          for (int r = 0; r < 3; ++r)
            for (int a = 0; a < 3; ++a) e[r][a] = x(v[r + 1], a) - x(v[0], a);
          const double det = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                             e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                             e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
          if (det < 0) std::swap(v[2], v[3]);
          mesh.tets.insert(mesh.tets.end(), v, v + 4);
        }
      }
  return mesh;
}

// A deterministic state per environment: squeezed along z by up to 30 % and jittered by up to
// 15 % of a cell, so that many tets need their Hessian projected.
std::vector<double> deformed_state(const BoxMesh& mesh, int environments, double cell) {
  std::vector<double> q;
  std::uint64_t seed = 0x9e3779b97f4a7c15ull;
  const auto uniform = [&] {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(seed >> 11) / static_cast<double>(1ull << 53) - 0.5;
  };
  for (int e = 0; e < environments; ++e) {
    const double squeeze = 1.0 - 0.3 * (e % 7) / 6.0;
    for (std::size_t v = 0; 3 * v < mesh.rest.size(); ++v) {
      for (int a = 0; a < 3; ++a) {
        const double scale = a == 2 ? squeeze : 1.0;
        q.push_back(scale * mesh.rest[3 * v + a] + 0.3 * cell * uniform());
      }
    }
  }
  return q;
}

struct StageValues {
  std::vector<double> environment_energy;
  std::vector<double> gradient;
  std::vector<double> hessian;
};

struct Timing {
  double device_ms = 0.0;  // median over repeats
  double host_ms = 0.0;
  double device_bytes = 0.0;
};

StageValues host_stages(const FemBatch& batch, const std::vector<double>& q, double& ms) {
  const TetBuffers tets = batch.tets();
  StageValues v;
  std::vector<double> tet_energy(tets.count), tet_gradient(12 * std::size_t(tets.count));
  v.hessian.resize(144 * std::size_t(tets.count));
  v.gradient.assign(q.size(), 0.0);
  v.environment_energy.resize(batch.environment_count());
  const auto start = std::chrono::steady_clock::now();
  launch_elastic_stages(SerialLauncher{}, tets, batch.incidence(), batch.tet_begin().data(),
                        batch.environment_count(), q.data(),
                        {tet_energy.data(), tet_gradient.data(), v.hessian.data(),
                         v.gradient.data(), v.environment_energy.data()});
  ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return v;
}

StageValues device_stages(const FemBatch& batch, const std::vector<double>& q, int repeats,
                          Timing& timing) {
  DeviceArray<int> dofs(batch.tet_dofs()), environment(batch.tet_environment());
  DeviceArray<double> dm(batch.rest_shape_inverse()), volume(batch.rest_volume()), mu(batch.mu()),
      lambda(batch.lambda());
  DeviceArray<int> vertex_dof(batch.vertex_dof()), begin(batch.incidence_begin()),
      slots(batch.incidence_slots()), tet_begin(batch.tet_begin());
  const int count = static_cast<int>(batch.rest_volume().size());
  DeviceArray<double> dq(q), tet_energy(count), tet_gradient(12 * std::size_t(count)),
      hessian(144 * std::size_t(count)), gradient(q.size()),
      environment_energy(batch.environment_count());
  const TetBuffers tets{count,         dofs.data(), environment.data(), dm.data(),
                        volume.data(), mu.data(),   lambda.data(),      nullptr};
  const IncidenceBuffers incidence{static_cast<int>(batch.vertex_dof().size()), vertex_dof.data(),
                                   begin.data(), slots.data()};
  timing.device_ms = device_median_ms(repeats, [&] {
    launch_elastic_stages(CudaLauncher{}, tets, incidence, tet_begin.data(),
                          batch.environment_count(), dq.data(),
                          {tet_energy.data(), tet_gradient.data(), hessian.data(), gradient.data(),
                           environment_energy.data()});
  });
  timing.device_bytes =
      8.0 * double(dq.size() + tet_energy.size() + tet_gradient.size() + hessian.size() +
                   gradient.size() + dm.size() + volume.size() + mu.size() + lambda.size()) +
      4.0 * double(dofs.size() + environment.size() + vertex_dof.size() + begin.size() +
                   slots.size());
  return {environment_energy.to_host(), gradient.to_host(), hessian.to_host()};
}

// The FEM vertices' inertia: targets from random velocities, each environment its own step and
// gravity; per vertex its energy, the batch's gradient (inertia alone), the targets.
struct InertiaValues {
  std::vector<double> energy, gradient, q_tilde;
};

struct InertiaInputs {
  std::vector<double> v, h, gravity;
};

InertiaInputs inertia_inputs(std::size_t dofs, int environments) {
  InertiaInputs in;
  std::uint64_t seed = 0x27d4eb2f165667c5ull;
  const auto uniform = [&] {  // in [-1, 1)
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    return 2.0 * static_cast<double>(seed >> 11) / static_cast<double>(1ull << 53) - 1.0;
  };
  for (std::size_t d = 0; d < dofs; ++d) in.v.push_back(0.5 * uniform());
  for (int e = 0; e < environments; ++e) {
    in.h.push_back(e % 2 ? 0.005 : 0.01);
    in.gravity.insert(in.gravity.end(), {0.5 * uniform(), 0.0, -9.81});
  }
  return in;
}

// The targets at the step's start q; the inertia at the state the step moved by 4 ms of its
// velocities (q_end), so that it is not zero.
template <class Launcher>
void inertia_stages(Launcher&& launch, const VertexBuffers& vertices, const double* q,
                    const double* q_end, const double* v, const double* h, const double* gravity,
                    double* q_tilde, double* energy, double* gradient) {
  launch(vertices.count, PredictionStage{vertices, q, v, h, gravity, q_tilde});
  launch(vertices.count, InertiaStage{vertices, q_end, q_tilde, energy, gradient});
}

std::vector<double> moved(const std::vector<double>& q, const std::vector<double>& v) {
  std::vector<double> q_end(q.size());
  for (std::size_t d = 0; d < q.size(); ++d) q_end[d] = q[d] + 0.004 * v[d];
  return q_end;
}

InertiaValues host_inertia(const FemBatch& batch, const std::vector<double>& q,
                           const InertiaInputs& in, double& ms) {
  const VertexBuffers vertices = batch.vertices();
  InertiaValues r{std::vector<double>(vertices.count), std::vector<double>(q.size(), 0.0),
                  std::vector<double>(q.size(), 0.0)};
  const std::vector<double> q_end = moved(q, in.v);
  const auto begin = std::chrono::steady_clock::now();
  inertia_stages(SerialLauncher{}, vertices, q.data(), q_end.data(), in.v.data(), in.h.data(),
                 in.gravity.data(), r.q_tilde.data(), r.energy.data(), r.gradient.data());
  ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin).count();
  return r;
}

InertiaValues device_inertia(const FemBatch& batch, const std::vector<double>& q,
                             const InertiaInputs& in, int repeats, double& ms) {
  DeviceArray<int> dof(batch.vertex_dof()), environment(batch.vertex_environment());
  DeviceArray<double> mass(batch.vertex_mass()), dq(q), q_end(moved(q, in.v)), v(in.v), h(in.h),
      gravity(in.gravity), q_tilde(q.size()), energy(batch.vertex_dof().size()), gradient(q.size());
  const VertexBuffers vertices{static_cast<int>(batch.vertex_dof().size()), dof.data(),
                               environment.data(), mass.data()};
  cuda_check(cudaMemset(q_tilde.data(), 0, q_tilde.size() * sizeof(double)), "cudaMemset");
  ms = device_median_ms(repeats, [&] {
    cuda_check(cudaMemset(gradient.data(), 0, gradient.size() * sizeof(double)), "cudaMemset");
    inertia_stages(CudaLauncher{}, vertices, dq.data(), q_end.data(), v.data(), h.data(),
                   gravity.data(), q_tilde.data(), energy.data(), gradient.data());
  });
  return {energy.to_host(), gradient.to_host(), q_tilde.to_host()};
}

constexpr int kPairsPerEnvironment = 512;

// Contact pairs per environment: a point above a triangle's centroid or two crossing edges (every
// third edge pair nearly parallel, so mollified), each at 5 % to 120 % of d_hat = 1 mm. Above
// the centroid, not above an edge: there the closest feature is a tie that round-off breaks
// either way, and the distance's Hessian differs between the two (it is C1 only).
ContactPairs contact_pairs(int environments, std::vector<double>& positions) {
  ContactPairs pairs;
  std::uint64_t seed = 0x2545f4914f6cdd1dull;
  const auto uniform = [&] {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(seed >> 11) / static_cast<double>(1ull << 53);
  };
  for (int e = 0; e < environments; ++e) {
    pairs.begin_environment(4 * kPairsPerEnvironment, 1e-3, 3e6);
    for (int k = 0; k < kPairsPerEnvironment; ++k) {
      const bool edge_edge = k % 2 == 1;
      const double d = (0.05 + 1.15 * uniform()) * 1e-3, angle = k % 6 == 1 ? 1e-3 : 1.0;
      double x[4][3] = {{edge_edge ? -0.006 : 0.0, 0.0, edge_edge ? 0.0 : d},
                        {edge_edge ? 0.006 : -0.004, edge_edge ? 0.0 : -0.003, 0.0},
                        {-0.005 * std::cos(angle), -0.005 * std::sin(angle), edge_edge ? d : 0.0},
                        {0.005 * std::cos(angle), 0.005 * std::sin(angle), edge_edge ? d : 0.0}};
      if (!edge_edge) {
        for (int a = 0; a < 2; ++a) x[0][a] = (x[1][a] + x[2][a] + x[3][a]) / 3.0;
      }
      for (const auto& v : x) positions.insert(positions.end(), {v[0], v[1], v[2]});
      const int vertex[4] = {4 * k, 4 * k + 1, 4 * k + 2, 4 * k + 3};
      pairs.add(edge_edge, vertex, 1e-3 * 0.012 * 0.01);  // eps_x: 1e-3 |ea|^2 |eb|^2
    }
  }
  return pairs;
}

// Per contact pair (or friction contact): energy, 12-gradient, 12x12 Hessian.
struct StageValues3 {
  std::vector<double> energy, gradient, hessian;
};
using BarrierValues = StageValues3;

BarrierValues host_barrier(const ContactPairs& pairs, const std::vector<double>& x, double& ms) {
  const int n = pairs.pairs().count;
  BarrierValues v{std::vector<double>(n), std::vector<double>(12 * std::size_t(n)),
                  std::vector<double>(144 * std::size_t(n))};
  const auto start = std::chrono::steady_clock::now();
  SerialLauncher{}(n, BarrierStage{pairs.pairs(), x.data(), nullptr, v.energy.data(),
                                   v.gradient.data(), v.hessian.data()});
  ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return v;
}

BarrierValues device_barrier(const ContactPairs& pairs, const std::vector<double>& x, int repeats,
                             double& ms, double& bytes) {
  DeviceArray<int> vertex(pairs.vertex()), environment(pairs.environment());
  DeviceArray<unsigned char> edge_edge(pairs.edge_edge());
  DeviceArray<double> eps(pairs.mollifier_eps()), d_hat(pairs.d_hat()), kappa(pairs.kappa()),
      positions(x);
  const int n = pairs.pairs().count;
  DeviceArray<double> energy(n), gradient(12 * std::size_t(n)), hessian(144 * std::size_t(n));
  const PairBuffers buffers{n,           vertex.data(),      edge_edge.data(),
                            eps.data(),  environment.data(), d_hat.data(),
                            kappa.data()};
  ms = device_median_ms(repeats, [&] {
    CudaLauncher{}(n, BarrierStage{buffers, positions.data(), nullptr, energy.data(),
                                   gradient.data(), hessian.data()});
  });
  bytes = 8.0 * double(positions.size() + eps.size() + energy.size() + gradient.size() +
                       hessian.size()) +
          4.0 * double(vertex.size() + environment.size()) + double(edge_edge.size());
  return {energy.to_host(), gradient.to_host(), hessian.to_host()};
}

// The same pairs as lagged friction contacts (normal +z, tangent basis x and y; a point over
// the triangle at barycentric (0.4, 0.3, 0.3), edges crossing at their midpoints), each with mu
// lambda from 0.1 to 50 N, and start positions from which the first vertex slid 0.1 to 10
// times eps_v h = 1e-5 m.
FrictionContacts friction_contacts(int environments, const std::vector<double>& positions,
                                   std::vector<double>& start) {
  constexpr double kEps = 1e-5;
  FrictionContacts contacts;
  std::uint64_t seed = 0x9e3779b97f4a7c15ull;
  const auto uniform = [&] {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(seed >> 11) / static_cast<double>(1ull << 53);
  };
  Eigen::Matrix<double, 3, 2> basis;
  basis << 1.0, 0.0, 0.0, 1.0, 0.0, 0.0;
  const Eigen::Matrix<double, 12, 2> point_triangle = grip::solver::kernels::tangent_operator<4>(
      grip::solver::kernels::point_triangle_relative_velocity_jacobian(Eigen::Vector2d(0.3, 0.3)),
      basis);
  const Eigen::Matrix<double, 12, 2> edge_edge = grip::solver::kernels::tangent_operator<4>(
      grip::solver::kernels::edge_edge_relative_velocity_jacobian(Eigen::Vector2d(0.5, 0.5)),
      basis);
  start = positions;
  for (int e = 0; e < environments; ++e) {
    contacts.begin_environment(4 * kPairsPerEnvironment, kEps);
    for (int k = 0; k < kPairsPerEnvironment; ++k) {
      const int vertex[4] = {4 * k, 4 * k + 1, 4 * k + 2, 4 * k + 3};
      contacts.add(vertex, k % 2 == 1 ? edge_edge : point_triangle, 0.1 + 50.0 * uniform());
      const double slide = std::pow(10.0, -1.0 + 2.0 * uniform()) * kEps, angle = 7.0 * k;
      const std::size_t first = 3 * (std::size_t(e) * 4 * kPairsPerEnvironment + 4 * k);
      start[first] -= slide * std::cos(angle);
      start[first + 1] -= slide * std::sin(angle);
    }
  }
  return contacts;
}

StageValues3 host_friction(const FrictionContacts& contacts, const std::vector<double>& x,
                           const std::vector<double>& start, double& ms) {
  const int n = contacts.buffers().count;
  StageValues3 v{std::vector<double>(n), std::vector<double>(12 * std::size_t(n)),
                 std::vector<double>(144 * std::size_t(n))};
  const auto begin = std::chrono::steady_clock::now();
  SerialLauncher{}(n, FrictionStage{contacts.buffers(), x.data(), start.data(), v.energy.data(),
                                    v.gradient.data(), v.hessian.data()});
  ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin).count();
  return v;
}

StageValues3 device_friction(const FrictionContacts& contacts, const std::vector<double>& x,
                             const std::vector<double>& start, int repeats, double& ms,
                             double& bytes) {
  DeviceArray<int> vertex(contacts.vertex()), environment(contacts.environment());
  DeviceArray<double> tangent(contacts.tangent()), mu_lambda(contacts.mu_lambda()),
      eps(contacts.eps()), positions(x), start_positions(start);
  const int n = contacts.buffers().count;
  DeviceArray<double> energy(n), gradient(12 * std::size_t(n)), hessian(144 * std::size_t(n));
  const FrictionBuffers buffers{
      n, vertex.data(), tangent.data(), mu_lambda.data(), environment.data(), eps.data()};
  ms = device_median_ms(repeats, [&] {
    CudaLauncher{}(n, FrictionStage{buffers, positions.data(), start_positions.data(),
                                    energy.data(), gradient.data(), hessian.data()});
  });
  bytes = 8.0 * double(positions.size() + start_positions.size() + tangent.size() +
                       mu_lambda.size() + energy.size() + gradient.size() + hessian.size()) +
          4.0 * double(vertex.size() + environment.size());
  return {energy.to_host(), gradient.to_host(), hessian.to_host()};
}

constexpr int kAffinePerEnvironment = 17;  // a LEAP hand's 16 driven links and its object

// Per environment 17 boxes of 1 to 5 cm as affine bodies, the first falling (the object), the
// others driven (the links), each with the analytic mass matrix of a box about its centre
// (m I for p, the second moments for the rows of A) and its diagonal inverse; states whose
// matrices are scaled by 0.8 to 1.2 and jittered, so that some orthogonality Hessians need
// projecting; random velocities, and drive targets off the state by up to 5 mm.
struct AffineScene {
  AffineBatch batch;
  std::vector<double> q, v, target, h, gravity;
};

AffineScene affine_scene(int environments) {
  AffineScene scene;
  std::uint64_t seed = 0x853c49e6748fea9bull;
  const auto uniform = [&] {  // in [-1, 1)
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    return 2.0 * static_cast<double>(seed >> 11) / static_cast<double>(1ull << 53) - 1.0;
  };
  for (int e = 0; e < environments; ++e) {
    scene.batch.begin_environment(12 * kAffinePerEnvironment);
    scene.h.push_back(e % 2 ? 0.005 : 0.01);
    scene.gravity.insert(scene.gravity.end(), {0.5 * uniform(), 0.0, -9.81});
    for (int b = 0; b < kAffinePerEnvironment; ++b) {
      const double size[3] = {0.03 + 0.02 * uniform(), 0.03 + 0.02 * uniform(),
                              0.03 + 0.02 * uniform()};
      const double density = 1000.0, volume = size[0] * size[1] * size[2], mass = density * volume;
      std::vector<double> m(144, 0.0), inverse(144, 0.0);
      for (int k = 0; k < 12; ++k) {
        const double diagonal = k < 3 ? mass : mass * size[(k - 3) % 3] * size[(k - 3) % 3] / 12.0;
        m[13 * k] = diagonal;
        inverse[13 * k] = 1.0 / diagonal;
      }
      scene.batch.add_body(
          12 * b, {m.data(), inverse.data(), density, volume, 1e9, b == 0, b == 0 ? 0.0 : 2e4});
      for (int k = 0; k < 12; ++k) {
        const double identity = k >= 3 && (k - 3) % 4 == 0 ? 1.0 : 0.0;
        const double x =
            k < 3 ? 0.1 * uniform() : identity * (1.0 + 0.2 * uniform()) + 0.1 * uniform();
        scene.q.push_back(x);
        scene.v.push_back(0.3 * uniform());
        scene.target.push_back(x + 0.005 * uniform());
      }
    }
  }
  return scene;
}

// Per body its three energies (inertia, orthogonality, drive, one after the other), the
// batch's inertia target and gradient (the three stages' sum), the 81-value Hessian blocks.
struct AffineValues {
  std::vector<double> energy, q_tilde, gradient, hessian;
};

// The four affine stages in order, with `launch`; the gradient must start at zero.
template <class Launcher>
void affine_stages(Launcher&& launch, const AffineBuffers& bodies, const double* q, const double* v,
                   const double* target, const double* h, const double* gravity, double* q_tilde,
                   double* energy, double* gradient, double* hessian) {
  launch(bodies.count, AffinePredictionStage{bodies, q, v, h, gravity, q_tilde});
  launch(bodies.count, AffineInertiaStage{bodies, q, q_tilde, energy, gradient});
  launch(bodies.count,
         OrthogonalityStage{bodies, q, true, energy + bodies.count, gradient, hessian});
  launch(bodies.count, DriveStage{bodies, q, target, energy + 2 * bodies.count, gradient});
}

AffineValues host_affine(const AffineScene& a, double& ms) {
  const int n = a.batch.bodies().count;
  AffineValues v{std::vector<double>(3 * std::size_t(n)), std::vector<double>(a.q.size()),
                 std::vector<double>(a.q.size(), 0.0), std::vector<double>(81 * std::size_t(n))};
  const auto begin = std::chrono::steady_clock::now();
  affine_stages(SerialLauncher{}, a.batch.bodies(), a.q.data(), a.v.data(), a.target.data(),
                a.h.data(), a.gravity.data(), v.q_tilde.data(), v.energy.data(), v.gradient.data(),
                v.hessian.data());
  ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin).count();
  return v;
}

AffineValues device_affine(const AffineScene& a, int repeats, double& ms, double& bytes) {
  const AffineBatch& batch = a.batch;
  DeviceArray<int> dof(batch.dof()), environment(batch.environment());
  DeviceArray<double> m(batch.mass_matrix()), inverse(batch.mass_matrix_inverse()),
      weight(batch.weight_mass()), volume(batch.volume()),
      stiffness(batch.orthogonality_stiffness()), drive(batch.drive_stiffness()), q(a.q), v(a.v),
      target(a.target), h(a.h), gravity(a.gravity);
  const int n = batch.bodies().count;
  DeviceArray<double> q_tilde(a.q.size()), energy(3 * std::size_t(n)), gradient(a.q.size()),
      hessian(81 * std::size_t(n));
  const AffineBuffers bodies{n,
                             dof.data(),
                             environment.data(),
                             m.data(),
                             inverse.data(),
                             weight.data(),
                             volume.data(),
                             stiffness.data(),
                             drive.data()};
  ms = device_median_ms(repeats, [&] {
    cuda_check(cudaMemset(gradient.data(), 0, gradient.size() * sizeof(double)), "cudaMemset");
    affine_stages(CudaLauncher{}, bodies, q.data(), v.data(), target.data(), h.data(),
                  gravity.data(), q_tilde.data(), energy.data(), gradient.data(), hessian.data());
  });
  bytes = 8.0 * double(m.size() + inverse.size() + weight.size() + volume.size() +
                       stiffness.size() + drive.size() + q.size() + v.size() + target.size() +
                       q_tilde.size() + energy.size() + gradient.size() + hessian.size()) +
          4.0 * double(dof.size() + environment.size());
  return {energy.to_host(), q_tilde.to_host(), gradient.to_host(), hessian.to_host()};
}

// Per environment: the soft box's vertices (FEM, its DOFs first), the 8 corners of each of the
// affine scene's bodies (their DOFs next), 8 scripted vertices a step's way from their start
// to their target; 512 contact pairs of four distinct vertices with random gradients.
struct MapScene {
  CollisionBatch batch;
  std::vector<double> q, start, target, progress, pair_gradient, pair_hessian;
  std::vector<int> pair_vertex;
  ContactIncidence incidence;
  StencilSlots slots;    // the pairs as stencils
  BlockPattern pattern;  // the pairs' Hessian blocks
};

MapScene map_scene(const BoxMesh& mesh, const std::vector<double>& fem_q, const AffineScene& affine,
                   int environments) {
  MapScene scene;
  std::uint64_t seed = 0xda3e39cb94b95bdbull;
  const auto uniform = [&] {  // in [0, 1)
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(seed >> 11) / static_cast<double>(1ull << 53);
  };
  const int fem_dofs = static_cast<int>(mesh.rest.size()), affine_dofs = 12 * kAffinePerEnvironment;
  for (int e = 0; e < environments; ++e) {
    scene.batch.begin_environment(fem_dofs + affine_dofs);
    scene.q.insert(scene.q.end(), fem_q.begin() + std::size_t(e) * fem_dofs,
                   fem_q.begin() + std::size_t(e + 1) * fem_dofs);
    scene.q.insert(scene.q.end(), affine.q.begin() + std::size_t(e) * affine_dofs,
                   affine.q.begin() + std::size_t(e + 1) * affine_dofs);
    for (int v = 0; 3 * v < fem_dofs; ++v) scene.batch.add_fem_vertex(3 * v);
    for (int b = 0; b < kAffinePerEnvironment; ++b) {
      for (int c = 0; c < 8; ++c) {
        scene.batch.add_affine_vertex(fem_dofs + 12 * b, c & 1 ? 0.01 : -0.01, c & 2 ? 0.01 : -0.01,
                                      c & 4 ? 0.01 : -0.01);
      }
    }
    for (int v = 0; v < 8; ++v) scene.batch.add_scripted_vertex();
    scene.progress.push_back(uniform());
  }
  for (int v = 0; v < scene.batch.vertex_count(); ++v) {
    for (int k = 0; k < 3; ++k) {
      scene.start.push_back(0.1 * uniform());
      scene.target.push_back(0.1 * uniform());
    }
  }
  for (int e = 0; e < environments; ++e) {
    const int first = scene.batch.vertex_begin()[e], n = scene.batch.vertex_begin()[e + 1] - first;
    for (int k = 0; k < kPairsPerEnvironment; ++k) {
      int four[4];
      for (int c = 0; c < 4; ++c) {
        bool repeated = true;
        while (repeated) {
          four[c] = first + std::min(n - 1, static_cast<int>(n * uniform()));
          repeated = std::find(four, four + c, four[c]) != four + c;
        }
      }
      scene.pair_vertex.insert(scene.pair_vertex.end(), four, four + 4);
      for (int c = 0; c < 12; ++c) scene.pair_gradient.push_back(2.0 * uniform() - 1.0);
      const std::size_t first_entry = scene.pair_hessian.size();
      scene.pair_hessian.resize(first_entry + 144);
      for (int r = 0; r < 12; ++r) {
        for (int c = 0; c <= r; ++c) {
          scene.pair_hessian[first_entry + 12 * c + r] =
              scene.pair_hessian[first_entry + 12 * r + c] = 2.0 * uniform() - 1.0;
        }
      }
    }
  }
  scene.incidence = contact_incidence(scene.batch, scene.pair_vertex.data(),
                                      static_cast<int>(scene.pair_vertex.size() / 4));
  add_contact_stencils(scene.batch, scene.pair_vertex.data(),
                       static_cast<int>(scene.pair_vertex.size() / 4), scene.slots);
  scene.pattern = block_pattern(scene.slots, scene.batch.dof_begin());
  return scene;
}

struct MapValues {
  std::vector<double> x, gradient;
};

template <class Launcher>
void map_stages(Launcher&& launch, const CollisionVertexBuffers& vertices,
                const ContactIncidenceBuffers& incidence, const double* q, const double* start,
                const double* target, const double* progress, const int* pair_vertex,
                const double* pair_gradient, double* x, double* gradient) {
  launch(vertices.count, PositionStage{vertices, q, start, target, progress, x});
  launch(incidence.count,
         ContactGatherStage{incidence, pair_vertex, vertices.rest, pair_gradient, gradient});
}

MapValues host_map(const MapScene& m, double& ms) {
  MapValues v{std::vector<double>(3 * std::size_t(m.batch.vertex_count())),
              std::vector<double>(m.q.size(), 0.0)};
  const auto begin = std::chrono::steady_clock::now();
  map_stages(SerialLauncher{}, m.batch.vertices(), incidence_buffers(m.batch, m.incidence),
             m.q.data(), m.start.data(), m.target.data(), m.progress.data(), m.pair_vertex.data(),
             m.pair_gradient.data(), v.x.data(), v.gradient.data());
  ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin).count();
  return v;
}

MapValues device_map(const MapScene& m, int repeats, double& ms, double& bytes) {
  const CollisionBatch& batch = m.batch;
  DeviceArray<unsigned char> motion(batch.motion());
  DeviceArray<int> dof(batch.dof()), environment(batch.environment()), block_dof(batch.block_dof()),
      block_size(batch.block_size()), begin(m.incidence.begin), slots(m.incidence.slots),
      pair_vertex(m.pair_vertex);
  DeviceArray<double> rest(batch.rest()), q(m.q), start(m.start), target(m.target),
      progress(m.progress), pair_gradient(m.pair_gradient),
      x(3 * std::size_t(batch.vertex_count())), gradient(m.q.size());
  const CollisionVertexBuffers vertices{batch.vertex_count(), motion.data(), dof.data(),
                                        rest.data(), environment.data()};
  const ContactIncidenceBuffers incidence{batch.block_count(), block_dof.data(), block_size.data(),
                                          begin.data(), slots.data()};
  ms = device_median_ms(repeats, [&] {
    cuda_check(cudaMemset(gradient.data(), 0, gradient.size() * sizeof(double)), "cudaMemset");
    map_stages(CudaLauncher{}, vertices, incidence, q.data(), start.data(), target.data(),
               progress.data(), pair_vertex.data(), pair_gradient.data(), x.data(),
               gradient.data());
  });
  bytes = 8.0 * double(rest.size() + q.size() + start.size() + target.size() + progress.size() +
                       pair_gradient.size() + x.size() + gradient.size()) +
          4.0 * double(dof.size() + environment.size() + block_dof.size() + block_size.size() +
                       begin.size() + slots.size() + pair_vertex.size()) +
          double(motion.size());
  return {x.to_host(), gradient.to_host()};
}

// The barrier's pairs on a path: each pair's second primitive (a point-triangle pair's point,
// an edge-edge pair's second edge) moved down by up to 2.5 mm towards the first, from its start
// 0.05 to 1.2 mm above it, so that about half of the pairs meet.
std::vector<double> ccd_end(const std::vector<double>& positions) {
  std::uint64_t seed = 0x5851f42d4c957f2dull;
  std::vector<double> end = positions;
  for (std::size_t k = 0; 12 * k < positions.size(); ++k) {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    const double drop = 2.5e-3 * static_cast<double>(seed >> 11) / static_cast<double>(1ull << 53);
    const bool edge_edge = k % 2 == 1;  // as contact_pairs alternates them
    for (int c = edge_edge ? 2 : 0; c < (edge_edge ? 4 : 1); ++c) end[12 * k + 3 * c + 2] -= drop;
  }
  return end;
}

// Per pair its time of impact, then per environment the bound.
struct CcdValues {
  std::vector<double> toi, bound;
};

template <class Launcher>
void ccd_stages(Launcher&& launch, int pairs, int environments, const int* vertex,
                const unsigned char* edge_edge, const int* pair_begin, const double* start,
                const double* end, double* toi, double* bound) {
  launch(pairs, CcdStage{vertex, edge_edge, start, end, 0.1, toi});
  launch(environments, EnvironmentMinStage{pair_begin, toi, bound});
}

CcdValues host_ccd(const ContactPairs& pairs, const std::vector<double>& start,
                   const std::vector<double>& end, double& ms) {
  const int n = pairs.pairs().count, environments = pairs.environment_count();
  CcdValues v{std::vector<double>(n), std::vector<double>(environments)};
  const auto begin = std::chrono::steady_clock::now();
  ccd_stages(SerialLauncher{}, n, environments, pairs.vertex().data(), pairs.edge_edge().data(),
             pairs.pair_begin().data(), start.data(), end.data(), v.toi.data(), v.bound.data());
  ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin).count();
  return v;
}

CcdValues device_ccd(const ContactPairs& pairs, const std::vector<double>& start,
                     const std::vector<double>& end, int repeats, double& ms) {
  const int n = pairs.pairs().count, environments = pairs.environment_count();
  DeviceArray<int> vertex(pairs.vertex()), pair_begin(pairs.pair_begin());
  DeviceArray<unsigned char> edge_edge(pairs.edge_edge());
  DeviceArray<double> x0(start), x1(end), toi(n), bound(environments);
  ms = device_median_ms(repeats, [&] {
    ccd_stages(CudaLauncher{}, n, environments, vertex.data(), edge_edge.data(), pair_begin.data(),
               x0.data(), x1.data(), toi.data(), bound.data());
  });
  return {toi.to_host(), bound.to_host()};
}

// The pairs' Hessians in 3x3 blocks: per block its 9 values.
std::vector<double> host_assembly(const MapScene& m, double& ms) {
  std::vector<double> blocks(9 * m.pattern.row.size());
  const auto begin = std::chrono::steady_clock::now();
  SerialLauncher{}(static_cast<int>(m.pattern.row.size()),
                   BlockAssemblyStage{m.pattern.buffers(), m.slots.rest.data(),
                                      m.pair_hessian.data(), blocks.data()});
  ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin).count();
  return blocks;
}

std::vector<double> device_assembly(const MapScene& m, int repeats, double& ms) {
  const BlockPattern& p = m.pattern;
  DeviceArray<int> row(p.row), column(p.column), begin(p.begin), slots(p.term_slots),
      units(p.term_units);
  DeviceArray<double> rest(m.slots.rest), hessian(m.pair_hessian), blocks(9 * p.row.size());
  const BlockPatternBuffers pattern{static_cast<int>(p.row.size()),
                                    row.data(),
                                    column.data(),
                                    begin.data(),
                                    slots.data(),
                                    units.data()};
  ms = device_median_ms(repeats, [&] {
    CudaLauncher{}(pattern.count,
                   BlockAssemblyStage{pattern, rest.data(), hessian.data(), blocks.data()});
  });
  return blocks.to_host();
}

// Per environment the soft box's Newton matrix at its deformed state, M + h^2 K (h = 10 ms, K
// the elastic stages' projected Hessians), its bottom layer of vertices pinned, and a random
// right-hand side: a fin-ray finger's linear solve.
struct PcgScene {
  StencilSlots slots;
  BlockPattern pattern;
  std::vector<double> blocks, rhs, tolerance;
  std::vector<char> fixed;
};

PcgScene pcg_scene(const BoxMesh& mesh, const FemBatch& batch,
                   const std::vector<double>& tet_hessian) {
  PcgScene s;
  add_tet_stencils(batch, s.slots);
  s.pattern = block_pattern(s.slots, batch.dof_begin());
  constexpr double kStep = 0.01;
  std::vector<double> scaled(tet_hessian.size());
  for (std::size_t k = 0; k < scaled.size(); ++k) scaled[k] = kStep * kStep * tet_hessian[k];
  s.blocks.resize(9 * s.pattern.row.size());
  SerialLauncher launch;
  launch(
      static_cast<int>(s.pattern.row.size()),
      BlockAssemblyStage{s.pattern.buffers(), s.slots.rest.data(), scaled.data(), s.blocks.data()});
  std::vector<int> units;
  for (const int dof : batch.vertex_dof()) units.push_back(dof / 3);
  const std::vector<int> diagonal = s.pattern.diagonal_blocks(units);
  launch(batch.vertices().count,
         MassDiagonalStage{batch.vertices(), diagonal.data(), s.blocks.data()});
  std::uint64_t seed = 0x9e3779b97f4a7c15ull;
  for (int e = 0; e < batch.environment_count(); ++e) {
    for (std::size_t v = 0; 3 * v < mesh.rest.size(); ++v) {
      const bool pinned = mesh.rest[3 * v + 2] == 0.0;
      for (int k = 0; k < 3; ++k) {
        seed = seed * 6364136223846793005ull + 1442695040888963407ull;
        s.fixed.push_back(pinned ? 1 : 0);
        s.rhs.push_back(2.0 * static_cast<double>(seed >> 11) / static_cast<double>(1ull << 53) -
                        1.0);
      }
    }
  }
  s.tolerance.assign(batch.environment_count(), kPcgResidual);
  return s;
}

struct PcgValues {
  std::vector<double> x;
  std::vector<int> status, iterations;
};

PcgValues host_pcg(const PcgScene& s, const FemBatch& batch, double& ms) {
  HostPcg pcg(batch, AffineBatch{}, s.pattern, batch.dof_begin());
  PcgValues v{std::vector<double>(s.rhs.size(), 0.0), {}, {}};
  SerialLauncher launch;
  const auto begin = std::chrono::steady_clock::now();
  pcg.solve(launch, s.blocks, s.fixed, s.rhs, s.tolerance, kPcgMaxIterations, v.x);
  ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin).count();
  v.status = pcg.status();
  v.iterations = pcg.iterations();
  return v;
}

PcgValues device_pcg(const PcgScene& s, const FemBatch& batch, int repeats, double& ms,
                     double& bytes) {
  PcgStorage<DeviceArray> device(
      pcg_structure(batch, AffineBatch{}, s.pattern, batch.dof_begin(), kCoarseAggregateVertices));
  DeviceArray<char> fixed(s.fixed);
  DeviceArray<double> blocks(s.blocks), rhs(s.rhs), tolerance(s.tolerance), x(s.rhs.size());
  const PcgBuffers p = device.buffers(blocks.data(), fixed.data(), rhs.data(), tolerance.data(),
                                      kPcgMaxIterations, x.data());
  CudaLauncher launch;
  ms = device_median_ms(repeats, [&] {
    cuda_check(cudaMemset(x.data(), 0, x.size() * sizeof(double)), "cudaMemset");
    solve_block_pcg(launch, p);
  });
  bytes = device.bytes() + double(fixed.size()) +
          8.0 * double(blocks.size() + rhs.size() + tolerance.size() + x.size());
  return {x.to_host(), device.status.to_host(), device.iterations.to_host()};
}

struct SizeResult {
  int environments = 0;
  int tets = 0;
  Timing timing;
  double energy = 0.0, gradient = 0.0, hessian = 0.0;  // relative differences
  double barrier_device_ms = 0.0, barrier_host_ms = 0.0, barrier_bytes = 0.0;
  double barrier_energy = 0.0, barrier_gradient = 0.0, barrier_hessian = 0.0;
  double friction_device_ms = 0.0, friction_host_ms = 0.0, friction_bytes = 0.0;
  double friction_energy = 0.0, friction_gradient = 0.0, friction_hessian = 0.0;
  double affine_device_ms = 0.0, affine_host_ms = 0.0, affine_bytes = 0.0;
  double affine_target = 0.0, affine_energy = 0.0, affine_gradient = 0.0, affine_hessian = 0.0;
  double map_device_ms = 0.0, map_host_ms = 0.0, map_bytes = 0.0;
  double map_position = 0.0, map_gradient = 0.0;
  double assembly_device_ms = 0.0, assembly_host_ms = 0.0, assembly = 0.0;
  int blocks = 0;
  double ccd_device_ms = 0.0, ccd_host_ms = 0.0, ccd_toi = 0.0, ccd_bound = 0.0;
  double inertia_device_ms = 0.0, inertia_host_ms = 0.0;
  double inertia_target = 0.0, inertia_energy = 0.0, inertia_gradient = 0.0;
  int ccd_impacts = 0;  // pairs that met on their path (host)
  double pcg_device_ms = 0.0, pcg_host_ms = 0.0, pcg_bytes = 0.0, pcg_solution = 0.0;
  int pcg_iterations = 0;            // the most any environment took (host)
  int pcg_iteration_difference = 0;  // the largest |device - host| over environments
  bool pcg_converged = false;        // every environment, on both
  BroadPhaseCheck broad_phase;
  double halving_device_ms = 0.0, halving_host_ms = 0.0;
  int halving_most = 0;            // the most halvings any environment took (host)
  bool halving_identical = false;  // every environment's alpha and halvings, device and host
  PotentialCheck potential;
  DenseCheck dense;
  bool pass() const {
    // The friction Hessian needs no eigen-solve: it is held to the gradient's tolerance.
    return energy <= kEnergyTolerance && gradient <= kGradientTolerance &&
           hessian <= kHessianTolerance && barrier_energy <= kEnergyTolerance &&
           barrier_gradient <= kGradientTolerance && barrier_hessian <= kHessianTolerance &&
           friction_energy <= kEnergyTolerance && friction_gradient <= kGradientTolerance &&
           friction_hessian <= kGradientTolerance && affine_target <= kGradientTolerance &&
           affine_energy <= kEnergyTolerance && affine_gradient <= kGradientTolerance &&
           affine_hessian <= kHessianTolerance && map_position <= kGradientTolerance &&
           map_gradient <= kGradientTolerance && assembly <= kGradientTolerance &&
           ccd_toi <= kCcdTolerance && ccd_bound <= kCcdTolerance &&
           inertia_target <= kGradientTolerance && inertia_energy <= kEnergyTolerance &&
           inertia_gradient <= kGradientTolerance && pcg_converged &&
           pcg_solution <= kPcgTolerance && pcg_iteration_difference <= kPcgIterationSlack &&
           broad_phase.identical && broad_phase.lag_identical &&
           broad_phase.lag_difference <= kGradientTolerance && halving_identical &&
           potential.energy <= kEnergyTolerance && potential.gradient <= kGradientTolerance &&
           potential.hessian <= kHessianTolerance &&
           potential.kinematic_force <= kGradientTolerance && potential.decrease_identical &&
           dense.all_solved && dense.solution <= kGradientTolerance;
  }
};

// The contact stages (barrier, CCD, friction) over the same pairs.
void check_contacts(int environments, int repeats, SizeResult& result) {
  std::vector<double> positions;
  const ContactPairs pairs = contact_pairs(environments, positions);
  const BarrierValues on_device =
      device_barrier(pairs, positions, repeats, result.barrier_device_ms, result.barrier_bytes);
  const BarrierValues on_host = host_barrier(pairs, positions, result.barrier_host_ms);
  result.barrier_energy = relative_difference(on_device.energy, on_host.energy, 1);
  result.barrier_gradient = relative_difference(on_device.gradient, on_host.gradient, 12);
  result.barrier_hessian = relative_difference(on_device.hessian, on_host.hessian, 144);
  const std::vector<double> end = ccd_end(positions);
  const CcdValues ccd_device = device_ccd(pairs, positions, end, repeats, result.ccd_device_ms);
  const CcdValues ccd_host = host_ccd(pairs, positions, end, result.ccd_host_ms);
  result.ccd_toi = relative_difference(ccd_device.toi, ccd_host.toi, 1);
  result.ccd_bound = relative_difference(ccd_device.bound, ccd_host.bound, 1);
  result.ccd_impacts = static_cast<int>(
      std::count_if(ccd_host.toi.begin(), ccd_host.toi.end(), [](double t) { return t < 1.0; }));
  std::vector<double> start;
  const FrictionContacts contacts = friction_contacts(environments, positions, start);
  const StageValues3 friction_device = device_friction(
      contacts, positions, start, repeats, result.friction_device_ms, result.friction_bytes);
  const StageValues3 friction_host =
      host_friction(contacts, positions, start, result.friction_host_ms);
  result.friction_energy = relative_difference(friction_device.energy, friction_host.energy, 1);
  result.friction_gradient =
      relative_difference(friction_device.gradient, friction_host.gradient, 12);
  result.friction_hessian =
      relative_difference(friction_device.hessian, friction_host.hessian, 144);
}

// The affine stages, then the map over the soft box's DOFs (state q) and the affine bodies'.
void check_affine_and_map(const BoxMesh& mesh, const std::vector<double>& q, int environments,
                          int repeats, SizeResult& result) {
  const AffineScene affine = affine_scene(environments);
  const AffineValues affine_device =
      device_affine(affine, repeats, result.affine_device_ms, result.affine_bytes);
  const AffineValues affine_host = host_affine(affine, result.affine_host_ms);
  result.affine_target = relative_difference(affine_device.q_tilde, affine_host.q_tilde, 12);
  result.affine_energy = relative_difference(affine_device.energy, affine_host.energy, 1);
  result.affine_gradient = relative_difference(affine_device.gradient, affine_host.gradient, 12);
  result.affine_hessian = relative_difference(affine_device.hessian, affine_host.hessian, 81);
  const MapScene map = map_scene(mesh, q, affine, environments);
  const MapValues map_device = device_map(map, repeats, result.map_device_ms, result.map_bytes);
  const MapValues map_host = host_map(map, result.map_host_ms);
  result.map_position = relative_difference(map_device.x, map_host.x, 3);
  result.map_gradient = relative_difference(map_device.gradient, map_host.gradient, 12);
  const std::vector<double> blocks_device =
      device_assembly(map, repeats, result.assembly_device_ms);
  const std::vector<double> blocks_host = host_assembly(map, result.assembly_host_ms);
  result.assembly = relative_difference(blocks_device, blocks_host, 9);
  result.blocks = static_cast<int>(map.pattern.row.size());
}

// Per environment a random Newton step of up to 2 cm per DOF from the deformed state, halved
// from alpha = 1 until no tet inverts: each environment's kept alpha and halvings.
struct HalvingValues {
  std::vector<double> alpha;
  std::vector<int> halvings;
};

std::vector<double> newton_step(std::size_t dofs) {
  std::uint64_t seed = 0x2545f4914f6cdd1dull;
  std::vector<double> p(dofs);
  for (double& x : p) {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    x = 0.02 * (2.0 * static_cast<double>(seed >> 11) / static_cast<double>(1ull << 53) - 1.0);
  }
  return p;
}

void check_halving(const FemBatch& batch, const std::vector<double>& q, int repeats,
                   SizeResult& result) {
  const int environments = batch.environment_count();
  const std::vector<double> p = newton_step(q.size());
  const TetBuffers host_tets = batch.tets();
  HalvingValues host{std::vector<double>(environments, 1.0), std::vector<int>(environments)};
  std::vector<int> status(environments);
  std::vector<double> ratio(host_tets.count), smallest(environments);
  int halving = 0;
  SerialLauncher serial;
  const auto begin = std::chrono::steady_clock::now();
  halve_until_no_inversion(serial, {host_tets, batch.tet_begin().data(), environments, q.data(),
                                    p.data(), host.alpha.data(), host.halvings.data(),
                                    status.data(), ratio.data(), smallest.data(), &halving});
  result.halving_host_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin).count();
  DeviceArray<int> dofs(batch.tet_dofs()), environment(batch.tet_environment()),
      tet_begin(batch.tet_begin()), device_halvings(environments), device_status(environments),
      device_halving(1);
  DeviceArray<double> dm(batch.rest_shape_inverse()), dq(q), dp(p), alpha(environments),
      device_ratio(host_tets.count), device_smallest(environments);
  const TetBuffers tets{host_tets.count, dofs.data(), environment.data(),
                        dm.data(),       nullptr,     nullptr,
                        nullptr,         nullptr};
  CudaLauncher launch;
  const std::vector<double> ones(environments, 1.0);
  result.halving_device_ms = device_median_ms(repeats, [&] {
    cuda_check(
        cudaMemcpy(alpha.data(), ones.data(), ones.size() * sizeof(double), cudaMemcpyHostToDevice),
        "cudaMemcpy to the device");
    halve_until_no_inversion(
        launch, {tets, tet_begin.data(), environments, dq.data(), dp.data(), alpha.data(),
                 device_halvings.data(), device_status.data(), device_ratio.data(),
                 device_smallest.data(), device_halving.data()});
  });
  result.halving_identical =
      alpha.to_host() == host.alpha && device_halvings.to_host() == host.halvings;
  result.halving_most = *std::max_element(host.halvings.begin(), host.halvings.end());
}

// The soft box's linear solves by the two-level CG.
void check_pcg(const BoxMesh& mesh, const FemBatch& batch, const std::vector<double>& tet_hessian,
               int repeats, SizeResult& result) {
  const PcgScene scene = pcg_scene(mesh, batch, tet_hessian);
  const PcgValues on_device =
      device_pcg(scene, batch, repeats, result.pcg_device_ms, result.pcg_bytes);
  const PcgValues on_host = host_pcg(scene, batch, result.pcg_host_ms);
  result.pcg_solution = relative_difference(on_device.x, on_host.x, mesh.rest.size());
  result.pcg_converged = true;
  for (std::size_t e = 0; e < on_host.status.size(); ++e) {
    result.pcg_converged = result.pcg_converged && on_host.status[e] == kPcgConverged &&
                           on_device.status[e] == kPcgConverged;
    result.pcg_iterations = std::max(result.pcg_iterations, on_host.iterations[e]);
    result.pcg_iteration_difference = std::max(
        result.pcg_iteration_difference, std::abs(on_device.iterations[e] - on_host.iterations[e]));
  }
}

// Body b of the affine scene's batch as AffineBatch::add_body takes it.
AffineBodyValues affine_values(const AffineBatch& batch, int b) {
  const double volume = batch.volume()[b], weight = batch.weight_mass()[b];
  return {batch.mass_matrix().data() + 144 * b,
          batch.mass_matrix_inverse().data() + 144 * b,
          weight > 0.0 ? weight / volume : 1000.0,
          volume,
          batch.orthogonality_stiffness()[b],
          weight > 0.0,
          batch.drive_stiffness()[b]};
}

// The map scene's pairs as barrier pairs (d_hat = 5 cm, so that most act) and as friction
// contacts lagged with the test's tangent frames and mu lambda of 0.5 to 5 N.
void add_potential_contacts(const MapScene& map, int environments, PotentialScene& s) {
  Eigen::Matrix<double, 3, 2> basis;
  basis << 1.0, 0.0, 0.0, 1.0, 0.0, 0.0;
  const Eigen::Matrix<double, 12, 2> tangent = grip::solver::kernels::tangent_operator<4>(
      grip::solver::kernels::point_triangle_relative_velocity_jacobian(Eigen::Vector2d(0.3, 0.3)),
      basis);
  for (int e = 0; e < environments; ++e) {
    const int first = map.batch.vertex_begin()[e], n = map.batch.vertex_begin()[e + 1] - first;
    s.pairs.begin_environment(n, 0.05, 1e3);
    s.friction.begin_environment(n, 1e-5);
    for (int k = e * kPairsPerEnvironment; k < (e + 1) * kPairsPerEnvironment; ++k) {
      int vertex[4];
      for (int c = 0; c < 4; ++c) vertex[c] = map.pair_vertex[4 * k + c] - first;
      s.pairs.add(k % 2 == 1, vertex, 1e-9);
      s.friction.add(vertex, tangent, 0.5 + 4.5 * double(k % 10) / 9.0);
    }
  }
}

// The step's constants from the map scene's state (its start) and the inertia inputs'
// velocities, computed by the host launcher's stages (fill_step_start_constants): inertia
// targets, the damping's stiffness, the collision vertices' start positions.
void add_step_constants(const std::vector<double>& v, const std::vector<double>& gravity,
                        PotentialScene& s) {
  fill_step_start_constants(s.step, s.fem, s.affine, s.collision, v, gravity);
  s.q = moved(s.step.q_start, v);
}

// The incremental potential's scene: each environment's soft box (damped, beta = 5 ms) and
// affine bodies in one batch, with the map scene's collision vertices and pairs.
PotentialScene potential_scene(const BoxMesh& mesh, const std::vector<double>& fem_q,
                               int environments) {
  const AffineScene affine = affine_scene(environments);
  const MapScene map = map_scene(mesh, fem_q, affine, environments);
  const InertiaInputs inertia = inertia_inputs(fem_q.size(), environments);
  const std::size_t fem_dofs = mesh.rest.size(), affine_dofs = 12 * kAffinePerEnvironment;
  PotentialScene s;
  s.collision = map.batch;
  std::vector<double> v;
  for (int e = 0; e < environments; ++e) {
    s.fem.begin_environment(static_cast<int>(fem_dofs + affine_dofs));
    s.fem.add_body(0, mesh.rest, mesh.tets, {9.4e6, 0.45, 1100.0, 5e-3});
    s.affine.begin_environment(static_cast<int>(fem_dofs + affine_dofs));
    for (int b = 0; b < kAffinePerEnvironment; ++b) {
      s.affine.add_body(static_cast<int>(fem_dofs) + 12 * b,
                        affine_values(affine.batch, e * kAffinePerEnvironment + b));
    }
    v.insert(v.end(), inertia.v.begin() + e * fem_dofs, inertia.v.begin() + (e + 1) * fem_dofs);
    v.insert(v.end(), affine.v.begin() + e * affine_dofs, affine.v.begin() + (e + 1) * affine_dofs);
    s.step.drive_target.insert(s.step.drive_target.end(), fem_dofs, 0.0);
    s.step.drive_target.insert(s.step.drive_target.end(), affine.target.begin() + e * affine_dofs,
                               affine.target.begin() + (e + 1) * affine_dofs);
    s.step.h.push_back(affine.h[e]);
    s.step.progress.push_back(map.progress[e]);  // scripted vertices part way: motion to come
  }
  s.fem.finish();
  s.step.q_start = map.q;
  s.step.scripted_start = map.start;
  s.step.scripted_target = map.target;
  add_potential_contacts(map, environments, s);
  add_step_constants(v, affine.gravity, s);
  return s;
}

SizeResult check_size(const BoxMesh& mesh, int environments, int repeats, double cell) {
  FemBatch batch;
  const int dofs = static_cast<int>(mesh.rest.size());
  for (int e = 0; e < environments; ++e) {
    batch.begin_environment(dofs);
    batch.add_body(0, mesh.rest, mesh.tets, {9.4e6, 0.45, 1100.0, 0.0});
  }
  batch.finish();
  const std::vector<double> q = deformed_state(mesh, environments, cell);
  SizeResult result;
  result.environments = environments;
  result.tets = static_cast<int>(batch.rest_volume().size());
  const StageValues device = device_stages(batch, q, repeats, result.timing);
  const StageValues host = host_stages(batch, q, result.timing.host_ms);
  result.energy = relative_difference(device.environment_energy, host.environment_energy, 1);
  result.gradient = relative_difference(device.gradient, host.gradient, q.size());
  result.hessian = relative_difference(device.hessian, host.hessian, 144);
  const InertiaInputs inputs = inertia_inputs(q.size(), environments);
  const InertiaValues inertia_device =
      device_inertia(batch, q, inputs, repeats, result.inertia_device_ms);
  const InertiaValues inertia_host = host_inertia(batch, q, inputs, result.inertia_host_ms);
  result.inertia_target = relative_difference(inertia_device.q_tilde, inertia_host.q_tilde, 3);
  result.inertia_energy = relative_difference(inertia_device.energy, inertia_host.energy, 1);
  result.inertia_gradient = relative_difference(inertia_device.gradient, inertia_host.gradient, 3);
  check_contacts(environments, repeats, result);
  check_affine_and_map(mesh, q, environments, repeats, result);
  check_pcg(mesh, batch, host.hessian, repeats, result);
  result.broad_phase = check_broad_phase(environments, repeats);
  check_halving(batch, q, repeats, result);
  result.potential = check_potential(potential_scene(mesh, q, environments), repeats);
  result.dense = check_dense_cholesky(environments, repeats);
  return result;
}

std::vector<int> parse_sizes(const std::string& text) {
  std::vector<int> sizes;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) sizes.push_back(std::stoi(item));
  return sizes;
}

std::string device_description(std::string& name) {
  cudaDeviceProp properties{};
  cuda_check(cudaGetDeviceProperties(&properties, 0), "cudaGetDeviceProperties");
  int driver = 0, runtime = 0;
  cudaDriverGetVersion(&driver);
  cudaRuntimeGetVersion(&runtime);
  name = properties.name;
  std::ostringstream out;
  out << "\"gpu\": \"" << properties.name
      << "\", \"memory_gib\": " << properties.totalGlobalMem / double(1ull << 30)
      << ", \"driver\": " << driver << ", \"runtime\": " << runtime;
  return out.str();
}

// The broad phase's and the line search's fields of a row of gpu-check.json.
void write_json_search(std::ostream& json, const SizeResult& r) {
  json << ", \"broad_phase_device_ms\": " << r.broad_phase.device_ms
       << ", \"broad_phase_host_ms\": " << r.broad_phase.host_ms
       << ", \"broad_phase_device_mib_per_environment\": "
       << r.broad_phase.bytes / r.environments / double(1 << 20)
       << ", \"broad_phase_pairs\": " << r.broad_phase.pairs
       << ", \"broad_phase_within_reach\": " << r.broad_phase.reachable
       << ", \"broad_phase_watched_by_ccd\": " << r.broad_phase.watched
       << ", \"broad_phase_identical\": " << (r.broad_phase.identical ? "true" : "false")
       << ", \"broad_phase_mismatch\": \"" << r.broad_phase.mismatch << "\""
       << ", \"friction_lag_contacts\": " << r.broad_phase.lagged
       << ", \"friction_lag_identical\": " << (r.broad_phase.lag_identical ? "true" : "false")
       << ", \"friction_lag_relative_difference\": " << r.broad_phase.lag_difference
       << ", \"halving_device_ms\": " << r.halving_device_ms
       << ", \"halving_host_ms\": " << r.halving_host_ms << ", \"halving_most\": " << r.halving_most
       << ", \"halving_identical\": " << (r.halving_identical ? "true" : "false")
       << ", \"potential_device_ms\": " << r.potential.device_ms
       << ", \"potential_host_ms\": " << r.potential.host_ms
       << ", \"potential_energy_relative_difference\": " << r.potential.energy
       << ", \"newton_system_device_ms\": " << r.potential.derivatives_device_ms
       << ", \"newton_system_host_ms\": " << r.potential.derivatives_host_ms
       << ", \"newton_system_blocks\": " << r.potential.blocks
       << ", \"newton_gradient_relative_difference\": " << r.potential.gradient
       << ", \"newton_matrix_relative_difference\": " << r.potential.hessian
       << ", \"newton_matrix_own_block_relative_difference\": " << r.potential.hessian_own_block
       << ", \"kinematic_force_relative_difference\": " << r.potential.kinematic_force
       << ", \"decrease_device_ms\": " << r.potential.decrease_device_ms
       << ", \"decrease_host_ms\": " << r.potential.decrease_host_ms
       << ", \"decrease_fewest_halvings\": " << r.potential.fewest_halvings
       << ", \"decrease_most_halvings\": " << r.potential.most_halvings
       << ", \"decrease_identical\": " << (r.potential.decrease_identical ? "true" : "false")
       << ", \"dense_cholesky_device_ms\": " << r.dense.device_ms
       << ", \"dense_cholesky_host_ms\": " << r.dense.host_ms
       << ", \"dense_cholesky_dofs\": " << r.dense.dofs
       << ", \"dense_cholesky_relative_difference\": " << r.dense.solution
       << ", \"dense_cholesky_all_solved\": " << (r.dense.all_solved ? "true" : "false");
}

// One size's row of gpu-check.json.
void write_json_row(std::ostream& json, const SizeResult& r) {
  const auto mib = [&](double bytes) { return bytes / r.environments / double(1 << 20); };
  json << "{\"environments\": " << r.environments << ", \"tets\": " << r.tets
       << ", \"device_ms\": " << r.timing.device_ms << ", \"host_ms\": " << r.timing.host_ms
       << ", \"device_mib_per_environment\": " << mib(r.timing.device_bytes)
       << ", \"energy_relative_difference\": " << r.energy
       << ", \"gradient_relative_difference\": " << r.gradient
       << ", \"hessian_relative_difference\": " << r.hessian
       << ", \"pairs\": " << r.environments * kPairsPerEnvironment
       << ", \"barrier_device_ms\": " << r.barrier_device_ms
       << ", \"barrier_host_ms\": " << r.barrier_host_ms
       << ", \"barrier_device_mib_per_environment\": " << mib(r.barrier_bytes)
       << ", \"barrier_energy_relative_difference\": " << r.barrier_energy
       << ", \"barrier_gradient_relative_difference\": " << r.barrier_gradient
       << ", \"barrier_hessian_relative_difference\": " << r.barrier_hessian
       << ", \"friction_device_ms\": " << r.friction_device_ms
       << ", \"friction_host_ms\": " << r.friction_host_ms
       << ", \"friction_device_mib_per_environment\": " << mib(r.friction_bytes)
       << ", \"friction_energy_relative_difference\": " << r.friction_energy
       << ", \"friction_gradient_relative_difference\": " << r.friction_gradient
       << ", \"friction_hessian_relative_difference\": " << r.friction_hessian
       << ", \"affine_device_ms\": " << r.affine_device_ms
       << ", \"affine_host_ms\": " << r.affine_host_ms
       << ", \"affine_device_mib_per_environment\": " << mib(r.affine_bytes)
       << ", \"affine_target_relative_difference\": " << r.affine_target
       << ", \"affine_energy_relative_difference\": " << r.affine_energy
       << ", \"affine_gradient_relative_difference\": " << r.affine_gradient
       << ", \"affine_hessian_relative_difference\": " << r.affine_hessian
       << ", \"map_device_ms\": " << r.map_device_ms << ", \"map_host_ms\": " << r.map_host_ms
       << ", \"map_device_mib_per_environment\": " << mib(r.map_bytes)
       << ", \"map_position_relative_difference\": " << r.map_position
       << ", \"map_gradient_relative_difference\": " << r.map_gradient
       << ", \"hessian_blocks\": " << r.blocks
       << ", \"assembly_device_ms\": " << r.assembly_device_ms
       << ", \"assembly_host_ms\": " << r.assembly_host_ms
       << ", \"assembly_relative_difference\": " << r.assembly
       << ", \"ccd_device_ms\": " << r.ccd_device_ms << ", \"ccd_host_ms\": " << r.ccd_host_ms
       << ", \"ccd_impacts\": " << r.ccd_impacts
       << ", \"ccd_time_of_impact_relative_difference\": " << r.ccd_toi
       << ", \"ccd_bound_relative_difference\": " << r.ccd_bound
       << ", \"inertia_device_ms\": " << r.inertia_device_ms
       << ", \"inertia_host_ms\": " << r.inertia_host_ms
       << ", \"inertia_target_relative_difference\": " << r.inertia_target
       << ", \"inertia_energy_relative_difference\": " << r.inertia_energy
       << ", \"inertia_gradient_relative_difference\": " << r.inertia_gradient
       << ", \"pcg_device_ms\": " << r.pcg_device_ms << ", \"pcg_host_ms\": " << r.pcg_host_ms
       << ", \"pcg_device_mib_per_environment\": " << mib(r.pcg_bytes)
       << ", \"pcg_iterations\": " << r.pcg_iterations
       << ", \"pcg_iteration_difference\": " << r.pcg_iteration_difference
       << ", \"pcg_converged\": " << (r.pcg_converged ? "true" : "false")
       << ", \"pcg_solution_relative_difference\": " << r.pcg_solution;
  write_json_search(json, r);
  json << ", \"pass\": " << (r.pass() ? "true" : "false") << "}";
}

// One size's row of gpu-check.md.
void write_markdown_row(std::ostream& md, const SizeResult& r) {
  md << "| " << r.environments << " | " << r.tets << " | " << r.timing.device_ms << " | "
     << r.timing.host_ms << " | " << r.timing.host_ms / r.timing.device_ms << " | "
     << r.timing.device_bytes / r.environments / double(1 << 20) << " | " << r.energy << " | "
     << r.gradient << " | " << r.hessian << " | " << r.environments * kPairsPerEnvironment << " | "
     << r.barrier_device_ms << " | " << r.barrier_host_ms << " | " << r.barrier_energy << ", "
     << r.barrier_gradient << ", " << r.barrier_hessian << " | " << r.friction_device_ms << " | "
     << r.friction_host_ms << " | " << r.friction_energy << ", " << r.friction_gradient << ", "
     << r.friction_hessian << " | " << r.affine_device_ms << " | " << r.affine_host_ms << " | "
     << r.affine_target << ", " << r.affine_energy << ", " << r.affine_gradient << ", "
     << r.affine_hessian << " | " << r.map_device_ms << " | " << r.map_host_ms << " | "
     << r.map_position << ", " << r.map_gradient << " | " << r.blocks << " | "
     << r.assembly_device_ms << " | " << r.assembly_host_ms << " | " << r.assembly << " | "
     << r.ccd_device_ms << " | " << r.ccd_host_ms << " | " << r.ccd_impacts << " | " << r.ccd_toi
     << ", " << r.ccd_bound << " | " << r.inertia_device_ms << " | " << r.inertia_host_ms << " | "
     << r.inertia_target << ", " << r.inertia_energy << ", " << r.inertia_gradient << " | "
     << r.pcg_device_ms << " | " << r.pcg_host_ms << " | " << r.pcg_iterations << " | "
     << r.pcg_iteration_difference << " | " << r.pcg_solution << " | " << r.broad_phase.device_ms
     << " | " << r.broad_phase.host_ms << " | " << r.broad_phase.pairs << ", "
     << r.broad_phase.reachable << ", " << r.broad_phase.watched << " | "
     << (r.broad_phase.identical ? "yes" : "NO: " + r.broad_phase.mismatch) << " | "
     << r.broad_phase.lagged << " | " << (r.broad_phase.lag_identical ? "yes" : "NO") << ", "
     << r.broad_phase.lag_difference << " | " << r.halving_device_ms << " | " << r.halving_host_ms
     << " | " << r.halving_most << " | " << (r.halving_identical ? "yes" : "NO") << " | "
     << r.potential.device_ms << " | " << r.potential.host_ms << " | " << r.potential.energy
     << " | " << r.potential.derivatives_device_ms << " | " << r.potential.derivatives_host_ms
     << " | " << r.potential.blocks << " | " << r.potential.gradient << ", " << r.potential.hessian
     << ", " << r.potential.kinematic_force << " | " << r.potential.decrease_device_ms << " | "
     << r.potential.decrease_host_ms << " | " << r.potential.fewest_halvings << " to "
     << r.potential.most_halvings << " | " << (r.potential.decrease_identical ? "yes" : "NO")
     << " | " << r.dense.device_ms << " | " << r.dense.host_ms << " | " << r.dense.solution
     << (r.dense.all_solved ? "" : " (NOT all solved)") << " | " << (r.pass() ? "yes" : "NO")
     << " |\n";
}

// JSON has no infinity or NaN (a difference the check could not measure): they become null.
std::string finite_or_null(const std::string& json) {
  static const std::regex non_finite(R"((: |, |\[)-?(inf|nan)\b)");
  return std::regex_replace(json, non_finite, "$1null");
}

void write_reports(const std::string& directory, const std::string& device,
                   const std::string& gpu_name, const std::vector<SizeResult>& results,
                   int tets_per_environment) {
  std::ostringstream json;
  std::ofstream md(directory + "/gpu-check.md");
  if (!md) throw std::runtime_error("cannot write to " + directory);
  json << "{" << device << ", \"tets_per_environment\": " << tets_per_environment
       << ", \"stages\": \"elastic (energy, gradient, projected Hessian), gradient gather, "
          "environment energy; barrier; friction; affine (prediction, inertia, orthogonality, "
          "drive); map (positions, contact gradient gather, Hessian blocks); CCD (time of impact, "
          "step bound); "
          "FEM inertia (target, energy, gradient); two-level CG (block Jacobi and a coarse "
          "level over aggregates; the box's M + h^2 K, its bottom layer pinned); broad phase and "
          "reach filter (two facing sheets per "
          "environment); step halving until no tet inverts; incremental potential (every "
          "term, the box damped), Newton system (gradient, matrix blocks) and sufficient "
          "decrease\", "
          "\"pairs_per_environment\": "
       << kPairsPerEnvironment << ", \"affine_bodies_per_environment\": " << kAffinePerEnvironment
       << ", \"sizes\": [";
  md << "Elastic, FEM inertia, barrier, friction, affine, map, assembly, CCD, CG, broad-phase, "
        "step-halving, incremental-potential, Newton-system and sufficient-decrease stages on "
     << gpu_name << ": " << tets_per_environment << " tets, " << kPairsPerEnvironment
     << " contact pairs (and as many friction contacts) and " << kAffinePerEnvironment
     << " affine bodies per environment; host: one core, serial launcher.\n\n"
     << "| environments | tets | device ms | host ms | host/device | device MiB per env | "
        "energy diff | gradient diff | Hessian diff | pairs | barrier device ms | barrier host ms "
        "| barrier diffs (energy, gradient, Hessian) | friction device ms | friction host ms | "
        "friction diffs (energy, gradient, Hessian) | affine device ms | affine host ms | affine "
        "diffs (target, energy, gradient, Hessian) | map device ms | map host ms | map diffs "
        "(positions, gradient) | Hessian blocks | assembly device ms | assembly host ms | "
        "assembly diff | CCD device ms | CCD host ms | impacts | CCD diffs (time of "
        "impact, bound) | FEM inertia device ms | FEM inertia host ms | FEM inertia diffs "
        "(target, energy, gradient) | CG device ms | CG host ms | CG iterations | CG "
        "iteration diff | CG solution diff | broad phase device ms | broad phase host ms | "
        "candidates, within reach, watched by CCD | lists identical | lagged contacts | lag "
        "identical, diff | halving device ms | halving "
        "host ms | most halvings | halvings identical | potential device ms | potential host "
        "ms | potential diff | Newton system device ms | Newton system host ms | blocks | Newton "
        "system diffs (gradient, matrix per block row, kinematic force) | decrease device ms | "
        "decrease host ms "
        "| halvings | "
        "decrease "
        "identical | dense Cholesky device ms | dense Cholesky host ms | dense Cholesky diff | "
        "within tolerance |\n"
     << "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | "
        "--- | ---: | ---: | --- | ---: | ---: | --- | ---: | ---: | --- | ---: | ---: | ---: | "
        "---: | ---: | ---: | ---: | --- | ---: | ---: | --- | ---: | ---: | ---: | ---: | ---: "
        "| ---: | ---: | --- | --- | ---: | --- | ---: | ---: | ---: | --- | ---: | ---: | ---: "
        "| ---: | ---: | ---: | --- | ---: | ---: | --- | --- | ---: | ---: | ---: | --- |\n";
  for (std::size_t i = 0; i < results.size(); ++i) {
    if (i > 0) json << ", ";
    write_json_row(json, results[i]);
    write_markdown_row(md, results[i]);
  }
  json << "]}\n";
  std::ofstream(directory + "/gpu-check.json") << finite_or_null(json.str());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: grip-gpu-check OUTDIR [--sizes 1,8,64,256,512] [--repeats 5]\n";
    return 2;
  }
  const std::string directory = argv[1];
  std::vector<int> sizes{1, 8, 64, 256, 512};
  int repeats = 5;
  for (int a = 2; a + 1 < argc; a += 2) {
    const std::string flag = argv[a];
    if (flag == "--sizes") sizes = parse_sizes(argv[a + 1]);
    if (flag == "--repeats") repeats = std::max(1, std::stoi(argv[a + 1]));
  }
  int devices = 0;
  const cudaError_t status = cudaGetDeviceCount(&devices);
  if (status != cudaSuccess || devices == 0) {
    std::cerr << "grip-gpu-check: no CUDA device ("
              << (status != cudaSuccess ? cudaGetErrorString(status) : "none found")
              << "): run it on a machine with an NVIDIA GPU and its driver\n";
    return 2;
  }
  try {
    std::string gpu_name;
    const std::string device = device_description(gpu_name);
    constexpr double kCell = 0.004;  // a 32 x 16 x 48 mm box, about a fin-ray finger's tets
    const BoxMesh mesh = box_mesh(8, 4, 12, kCell);
    std::vector<SizeResult> results;
    bool pass = true;
    for (int environments : sizes) {
      results.push_back(check_size(mesh, environments, repeats, kCell));
      pass = pass && results.back().pass();
      std::cout << "environments " << environments << ": device " << results.back().timing.device_ms
                << " ms, host " << results.back().timing.host_ms << " ms, "
                << (results.back().pass() ? "within tolerance" : "OUTSIDE TOLERANCE") << "\n";
      // After every size, so that a run stopped at its time limit keeps the sizes it finished.
      write_reports(directory, device, gpu_name, results, static_cast<int>(mesh.tets.size() / 4));
    }
    return pass ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "grip-gpu-check: " << e.what() << "\n";
    return 2;
  }
}
