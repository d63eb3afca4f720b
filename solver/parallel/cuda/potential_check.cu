#include "solver/parallel/cuda/potential_check.cuh"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

#include "solver/parallel/cuda/cuda_launcher.cuh"
#include "solver/parallel/cuda/relative_difference.cuh"
#include "solver/parallel/derivative_stages.hpp"
#include "solver/parallel/launch.hpp"
#include "solver/parallel/line_search_stages.hpp"
#include "solver/parallel/prescribed_motion_stages.hpp"

namespace grip::solver::parallel {
namespace {

double milliseconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

std::vector<double> host_energies(const PotentialArrays<HostArray>& arrays,
                                  const std::vector<double>& q) {
  const PotentialBuffers b = arrays.buffers();
  PotentialStorage<HostArray> work(b);
  std::vector<double> energy(static_cast<std::size_t>(b.environment_count));
  SerialLauncher launch;
  incremental_potential(launch, b, q.data(), work.work(), energy.data());
  return energy;
}

// Per environment a random direction of up to 1 cm per DOF, turned downhill, and the gradient
// that gives it the energy's own slope along it, D = (E(q + eps p) - E(q - eps p)) / (2 eps):
// g = D p / |p|^2.
struct DownhillStep {
  std::vector<double> p, gradient;
};

DownhillStep downhill_step(const PotentialScene& s, const PotentialArrays<HostArray>& arrays) {
  DownhillStep step{std::vector<double>(s.q.size()), std::vector<double>(s.q.size())};
  std::uint64_t seed = 0x9e3779b97f4a7c15ull;
  for (double& x : step.p) {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    x = 0.01 * (2.0 * static_cast<double>(seed >> 11) / static_cast<double>(1ull << 53) - 1.0);
  }
  constexpr double kEps = 1e-7;
  std::vector<double> plus(s.q), minus(s.q);
  for (std::size_t d = 0; d < s.q.size(); ++d) {
    plus[d] += kEps * step.p[d];
    minus[d] -= kEps * step.p[d];
  }
  const std::vector<double> up = host_energies(arrays, plus), down = host_energies(arrays, minus);
  const std::vector<int>& begin = s.collision.dof_begin();
  for (std::size_t e = 0; e + 1 < begin.size(); ++e) {
    const double slope = (up[e] - down[e]) / (2.0 * kEps), sign = slope > 0.0 ? -1.0 : 1.0;
    double squared = 0.0;
    for (int d = begin[e]; d < begin[e + 1]; ++d) squared += step.p[d] * step.p[d];
    for (int d = begin[e]; d < begin[e + 1]; ++d) {
      step.p[d] *= sign;
      step.gradient[d] = sign * slope / squared * step.p[d];
    }
  }
  return step;
}

struct Search {
  std::vector<double> alpha;
  std::vector<int> halvings, status;
};

Search host_search(const PotentialScene& s, const PotentialArrays<HostArray>& arrays,
                   const DownhillStep& step, double& ms) {
  const PotentialBuffers b = arrays.buffers();
  PotentialStorage<HostArray> work(b);
  SufficientDecreaseStorage<HostArray> storage(s.collision.dof_begin());
  const std::vector<unsigned char> held(static_cast<std::size_t>(b.environment_count), 0);
  Search out{std::vector<double>(held.size(), 1.0), {}, {}};
  SerialLauncher launch;
  const auto start = std::chrono::steady_clock::now();
  sufficient_decrease(launch, storage.buffers(b, work.work(), s.q.data(), step.p.data(),
                                              step.gradient.data(), held.data(), out.alpha.data()));
  ms = milliseconds_since(start);
  out.halvings = storage.halvings;
  out.status = storage.status;
  return out;
}

Search device_search(const PotentialScene& s, const DownhillStep& step, int repeats, double& ms) {
  const PotentialArrays<DeviceArray> arrays(s.fem, s.affine, s.collision, s.pairs, s.friction,
                                            s.step);
  const PotentialBuffers b = arrays.buffers();
  PotentialStorage<DeviceArray> work(b);
  SufficientDecreaseStorage<DeviceArray> storage(s.collision.dof_begin());
  const std::vector<double> ones(static_cast<std::size_t>(b.environment_count), 1.0);
  DeviceArray<double> q(s.q), p(step.p), gradient(step.gradient), alpha(ones);
  const DeviceArray<unsigned char> held(std::vector<unsigned char>(ones.size(), 0));
  CudaLauncher launch;
  ms = device_median_ms(repeats, [&] {
    cuda_check(
        cudaMemcpy(alpha.data(), ones.data(), ones.size() * sizeof(double), cudaMemcpyHostToDevice),
        "cudaMemcpy to the device");
    sufficient_decrease(launch, storage.buffers(b, work.work(), q.data(), p.data(), gradient.data(),
                                                held.data(), alpha.data()));
  });
  return {alpha.to_host(), storage.halvings.to_host(), storage.status.to_host()};
}

std::vector<double> device_energies(const PotentialScene& s, int repeats, double& ms) {
  const PotentialArrays<DeviceArray> arrays(s.fem, s.affine, s.collision, s.pairs, s.friction,
                                            s.step);
  const PotentialBuffers b = arrays.buffers();
  PotentialStorage<DeviceArray> work(b);
  DeviceArray<double> q(s.q), energy(static_cast<std::size_t>(b.environment_count));
  CudaLauncher launch;
  ms = device_median_ms(
      repeats, [&] { incremental_potential(launch, b, q.data(), work.work(), energy.data()); });
  return energy.to_host();
}

// Every environment's gradient (the batch's DOFs), Newton matrix (9 per block) and force of
// the prescribed motion still to come (the batch's DOFs).
struct NewtonSystem {
  std::vector<double> gradient, blocks, kinematic_force;
};

template <template <class> class Array, class Launcher>
NewtonSystem newton_system(const PotentialScene& s, const DerivativeStructure& structure,
                           Launcher& launch, int repeats, double& ms) {
  const PotentialArrays<Array> arrays(s.fem, s.affine, s.collision, s.pairs, s.friction, s.step);
  const PotentialBuffers b = arrays.buffers();
  PotentialStorage<Array> work(b);
  DerivativeStorage<Array> storage(structure, s.fem, s.affine, s.collision);
  const Array<double> q(s.q);
  Array<double> gradient(s.q.size()), blocks(9 * structure.pattern.row.size());
  Array<double> motion(3 * std::size_t(s.collision.vertex_count()));
  Array<double> contact_force(3 * structure.contact_vertex.size()), force(s.q.size());
  const auto run = [&] {
    incremental_potential_derivatives(launch, b, storage.buffers(), q.data(), work.work(),
                                      storage.work(), nullptr, gradient.data(), blocks.data());
    kinematic_force(launch, b, storage.buffers(), work.work(), storage.work(), motion.data(),
                    contact_force.data(), force.data());
  };
  if constexpr (std::is_same_v<Launcher, CudaLauncher>) {
    ms = device_median_ms(repeats, run);
    return {gradient.to_host(), blocks.to_host(), force.to_host()};
  } else {
    const auto start = std::chrono::steady_clock::now();
    run();
    ms = milliseconds_since(start);
    return {gradient, blocks, force};
  }
}

// The largest |a - b| over the Newton matrices' 3x3 blocks, each relative to the largest |b| of
// its block row: where an assembled block's contributions cancel, its round-off is of its row's
// magnitude, not its own.
double block_row_difference(const std::vector<double>& a, const std::vector<double>& b,
                            const std::vector<int>& row) {
  if (a.size() != b.size() || b.size() != 9 * row.size()) {
    return std::numeric_limits<double>::infinity();
  }
  std::vector<double> scale(row.empty() ? 0 : *std::max_element(row.begin(), row.end()) + 1, 0.0);
  for (std::size_t i = 0; i < b.size(); ++i) {
    scale[row[i / 9]] = std::max(scale[row[i / 9]], std::abs(b[i]));
  }
  double worst = 0.0;
  for (std::size_t i = 0; i < b.size(); ++i) {
    const double d = std::abs(a[i] - b[i]);
    if (std::isnan(d)) return std::numeric_limits<double>::infinity();
    if (d > 0.0) worst = std::max(worst, d / std::max(scale[row[i / 9]], 1e-300));
  }
  return worst;
}

void check_derivatives(const PotentialScene& s, int repeats, PotentialCheck& check) {
  const DerivativeStructure structure =
      derivative_structure(s.fem, s.affine, s.collision, s.pairs, s.friction);
  SerialLauncher serial;
  CudaLauncher cuda;
  const NewtonSystem host =
      newton_system<HostArray>(s, structure, serial, repeats, check.derivatives_host_ms);
  const NewtonSystem device =
      newton_system<DeviceArray>(s, structure, cuda, repeats, check.derivatives_device_ms);
  check.gradient =
      relative_difference(device.gradient, host.gradient, std::size_t(s.collision.dof_begin()[1]));
  check.hessian = block_row_difference(device.blocks, host.blocks, structure.pattern.row);
  check.hessian_own_block = relative_difference(device.blocks, host.blocks, 9);
  check.kinematic_force = relative_difference(device.kinematic_force, host.kinematic_force,
                                              std::size_t(s.collision.dof_begin()[1]));
  check.blocks = static_cast<int>(structure.pattern.row.size());
}

}  // namespace

PotentialCheck check_potential(const PotentialScene& scene, int repeats) {
  PotentialCheck check;
  const PotentialArrays<HostArray> arrays(scene.fem, scene.affine, scene.collision, scene.pairs,
                                          scene.friction, scene.step);
  const auto start = std::chrono::steady_clock::now();
  const std::vector<double> host = host_energies(arrays, scene.q);
  check.host_ms = milliseconds_since(start);
  const std::vector<double> device = device_energies(scene, repeats, check.device_ms);
  check.energy = relative_difference(device, host, 1);
  check_derivatives(scene, repeats, check);
  const DownhillStep step = downhill_step(scene, arrays);
  const Search on_host = host_search(scene, arrays, step, check.decrease_host_ms);
  const Search on_device = device_search(scene, step, repeats, check.decrease_device_ms);
  check.decrease_identical = on_device.alpha == on_host.alpha &&
                             on_device.halvings == on_host.halvings &&
                             on_device.status == on_host.status;
  check.fewest_halvings = *std::min_element(on_host.halvings.begin(), on_host.halvings.end());
  check.most_halvings = *std::max_element(on_host.halvings.begin(), on_host.halvings.end());
  return check;
}

}  // namespace grip::solver::parallel
