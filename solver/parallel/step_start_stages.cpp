#include "solver/parallel/step_start_stages.hpp"

#include <utility>

namespace grip::solver::parallel {

void fill_step_start_constants(StepConstants& k, const FemBatch& fem, const AffineBatch& affine,
                               const CollisionBatch& collision, const std::vector<double>& v,
                               const std::vector<double>& gravity) {
  const std::vector<double> progress = std::exchange(k.progress, std::vector<double>(k.h.size()));
  const std::size_t tets = fem.rest_volume().size();
  k.q_tilde.assign(k.q_start.size(), 0.0);
  k.damping_stiffness.resize(144 * tets);
  k.start_positions.resize(3 * std::size_t(collision.vertex_count()));
  std::vector<double> energy(tets), gradient(12 * tets);
  // No contacts: the constants read none.
  const PotentialArrays<HostArray> arrays(fem, affine, collision, ContactPairs{},
                                          FrictionContacts{}, k);
  SerialLauncher launch;
  step_start_constants(launch, arrays.buffers(), v.data(), gravity.data(),
                       {k.q_tilde.data(), k.damping_stiffness.data(), k.start_positions.data(),
                        energy.data(), gradient.data()});
  k.progress = progress;
}

}  // namespace grip::solver::parallel
