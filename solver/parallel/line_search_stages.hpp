#pragma once
// The data-parallel line search's stages, every environment of a batch with its own step
// fraction alpha. First of them: halving alpha until no tet inverts at q + alpha p, as the CPU
// engine's halve_until_no_inversion does (solver/newton/line_search.hpp): an environment whose
// smallest det F is positive keeps its alpha; one whose alpha falls below 1e-12 fails. Each
// environment halves on its own and stops on its own, so its alpha and halvings are the same
// alone or in any batch; the host reads one number per round, how many environments still halve.
#include "solver/kernels/hd.hpp"
#include "solver/kernels/neo_hookean.hpp"
#include "solver/parallel/ccd_stages.hpp"
#include "solver/parallel/fem_batch.hpp"
#include "solver/parallel/launch.hpp"

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

}  // namespace grip::solver::parallel
