#pragma once
// The data-parallel line search's stages, every environment of a batch with its own step
// fraction alpha, as the CPU engine's filters (solver/newton/line_search.hpp) take them after
// CCD's bound:
// - halve_until_no_inversion: halving alpha until no tet inverts at q + alpha p; an environment
//   whose smallest det F is positive keeps its alpha.
// - sufficient_decrease: halving alpha until the incremental potential at q + alpha p falls by
//   Armijo's rule, E(q + alpha p) <= E(q) + 1e-4 alpha g.p, each environment with its own
//   energy and slope (potential_stages.hpp); an environment whose step is held (StepPolicy)
//   takes alpha as it is.
// An environment whose alpha falls below 1e-12 fails. Each environment halves on its own and
// stops on its own, so its alpha and halvings are the same alone or in any batch; the host reads
// one number per round, how many environments still halve.
#include <vector>

#include "solver/kernels/hd.hpp"
#include "solver/kernels/neo_hookean.hpp"
#include "solver/parallel/ccd_stages.hpp"
#include "solver/parallel/fem_batch.hpp"
#include "solver/parallel/launch.hpp"
#include "solver/parallel/potential_stages.hpp"

namespace grip::solver::parallel {

// What became of an environment's halving.
enum HalvingStatus : int { kHalving = 0, kNoInversion = 1, kStepTooSmall = 2 };

struct StepHalvingBuffers {
  TetBuffers tets;
  const int* tet_begin = nullptr;  // environments + 1 offsets
  int environment_count = 0;
  const double* q = nullptr;   // the batch's DOFs
  const double* p = nullptr;   // the Newton step
  double* alpha = nullptr;     // per environment: the first fraction on entry, the kept one after
  int* halvings = nullptr;     // per environment
  int* status = nullptr;       // per environment, a HalvingStatus
  double* ratio = nullptr;     // per tet: det F at q + alpha p
  double* smallest = nullptr;  // per environment: the smallest det F (1 without tets)
  int* halving = nullptr;      // one: how many environments still halve
};

struct HalvingResetStage {
  StepHalvingBuffers b;
  GRIP_HD void operator()(int e) const {
    b.status[e] = kHalving;
    b.halvings[e] = 0;
  }
};

// det F of tet t at its environment's trial point q + alpha p.
struct TrialDeterminantStage {
  StepHalvingBuffers b;

  GRIP_HD void operator()(int t) const {
    const int e = b.tets.environment[t];
    if (b.status[e] != kHalving) return;
    const double alpha = b.alpha[e];
    kernels::Vector12d x;
    for (int c = 0; c < 4; ++c) {
      const int dof = b.tets.dofs[4 * t + c];
      for (int k = 0; k < 3; ++k) x[3 * c + k] = b.q[dof + k] + alpha * b.p[dof + k];
    }
    const Eigen::Map<const Eigen::Matrix3d> dm_inverse(b.tets.rest_shape_inverse + 9 * t);
    const Eigen::Matrix3d rest_shape_inverse = dm_inverse;
    b.ratio[t] = kernels::deformation_gradient(x, rest_shape_inverse).determinant();
  }
};

struct HalvingStage {
  StepHalvingBuffers b;

  GRIP_HD void operator()(int e) const {
    if (b.status[e] != kHalving) return;
    if (b.smallest[e] > 0.0) {
      b.status[e] = kNoInversion;
      return;
    }
    b.alpha[e] *= 0.5;
    ++b.halvings[e];
    if (b.alpha[e] < 1e-12) b.status[e] = kStepTooSmall;
  }
};

template <class Launcher>
void halve_until_no_inversion(Launcher& launch, const StepHalvingBuffers& b) {
  launch(b.environment_count, HalvingResetStage{b});
  for (;;) {
    launch(b.tets.count, TrialDeterminantStage{b});
    launch(b.environment_count, EnvironmentMinStage{b.tet_begin, b.ratio, b.smallest});
    launch(b.environment_count, HalvingStage{b});
    launch(1, StatusCountStage{b.status, b.environment_count, kHalving, b.halving});
    if (launch.fetch(b.halving) == 0) return;
  }
}

// What became of an environment's search for sufficient decrease.
enum DecreaseStatus : int { kDecreasing = 0, kSufficientDecrease = 1, kNoDecrease = 2 };

struct SufficientDecreaseBuffers {
  PotentialBuffers potential;
  PotentialWork work;
  const int* dof_begin = nullptr;  // environments + 1 offsets into the batch's DOFs
  const double* q = nullptr;
  const double* p = nullptr;
  const double* gradient = nullptr;           // the batch's gradient at q
  const unsigned char* accept_any = nullptr;  // per environment: 1 where its step is held
  double* alpha = nullptr;   // per environment: the first fraction on entry, the kept one after
  int* halvings = nullptr;   // per environment
  int* status = nullptr;     // per environment, a DecreaseStatus
  double* trial = nullptr;   // the batch's DOFs at q + alpha p
  double* energy = nullptr;  // per environment: E(q)
  double* slope = nullptr;   // per environment: g.p
  double* trial_energy = nullptr;  // per environment: E(q + alpha p)
  int* decreasing = nullptr;       // one: how many environments still halve
};

// Per environment: g.p over its DOFs, and its search begun (a held step's at once accepted).
struct DecreaseResetStage {
  SufficientDecreaseBuffers b;

  GRIP_HD void operator()(int e) const {
    double slope = 0.0;
    for (int d = b.dof_begin[e]; d < b.dof_begin[e + 1]; ++d) slope += b.gradient[d] * b.p[d];
    b.slope[e] = slope;
    b.halvings[e] = 0;
    b.status[e] = b.accept_any[e] != 0 ? kSufficientDecrease : kDecreasing;
  }
};

// Per DOF of an environment still halving: q + alpha p.
struct TrialPointStage {
  SufficientDecreaseBuffers b;

  GRIP_HD void operator()(int d) const {
    const int e = environment_of(b.dof_begin, b.potential.environment_count, d);
    if (b.status[e] != kDecreasing) return;
    b.trial[d] = b.q[d] + b.alpha[e] * b.p[d];
  }
};

struct DecreaseStage {
  SufficientDecreaseBuffers b;

  GRIP_HD void operator()(int e) const {
    if (b.status[e] != kDecreasing) return;
    if (b.trial_energy[e] <= b.energy[e] + 1e-4 * b.alpha[e] * b.slope[e]) {
      b.status[e] = kSufficientDecrease;
      return;
    }
    b.alpha[e] *= 0.5;
    ++b.halvings[e];
    if (b.alpha[e] < 1e-12) b.status[e] = kNoDecrease;
  }
};

template <class Launcher>
void sufficient_decrease(Launcher& launch, const SufficientDecreaseBuffers& b) {
  const int environments = b.potential.environment_count;
  launch(environments, DecreaseResetStage{b});
  incremental_potential(launch, b.potential, b.q, b.work, b.energy);
  const int dofs = launch.fetch(b.dof_begin + environments);
  for (;;) {
    launch(1, StatusCountStage{b.status, environments, kDecreasing, b.decreasing});
    if (launch.fetch(b.decreasing) == 0) return;
    launch(dofs, TrialPointStage{b});
    incremental_potential(launch, b.potential, b.trial, b.work, b.trial_energy);
    launch(environments, DecreaseStage{b});
  }
}

// A search's arrays in host (HostArray) or device (DeviceArray) memory, for a batch whose
// environments' DOFs begin at `dof_begin` (environments + 1 offsets).
template <template <class> class Array>
struct SufficientDecreaseStorage {
  explicit SufficientDecreaseStorage(const std::vector<int>& dof_begin)
      : dof_begin(dof_begin),
        halvings(dof_begin.size() - 1),
        status(dof_begin.size() - 1),
        trial(std::size_t(dof_begin.back())),
        energy(dof_begin.size() - 1),
        slope(dof_begin.size() - 1),
        trial_energy(dof_begin.size() - 1),
        decreasing(std::size_t(1)) {}

  // The buffers of a search from q along p (gradient at q, per environment whether its step
  // is held, alpha its first fraction), the potential's in `potential` and `work`; all in this
  // storage's memory.
  SufficientDecreaseBuffers buffers(const PotentialBuffers& potential, const PotentialWork& work,
                                    const double* q, const double* p, const double* gradient,
                                    const unsigned char* accept_any, double* alpha) {
    return {potential,
            work,
            dof_begin.data(),
            q,
            p,
            gradient,
            accept_any,
            alpha,
            halvings.data(),
            status.data(),
            trial.data(),
            energy.data(),
            slope.data(),
            trial_energy.data(),
            decreasing.data()};
  }

  Array<int> dof_begin, halvings, status;
  Array<double> trial, energy, slope, trial_energy;
  Array<int> decreasing;
};

}  // namespace grip::solver::parallel
