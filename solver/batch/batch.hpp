#pragma once
// Many independent environments stepped together (GRIP, Section III-A). Each keeps its own
// scene, state, contact set, CCD step size, kappa, Newton counters and verdict. A batch step
// runs every environment's Newton iterations in rounds spread over threads: an environment
// whose Newton converged is frozen for the rest of the step and costs nothing while the others
// iterate; one that fails records why and leaves the batch. Environments never share mutable
// state, so each one's trajectory is bit-identical to a solo run of it, for any thread count.
// Environments built from one Model share its static part (rest shapes, DOF maps, masses,
// collision mesh, the fill-reducing ordering of the Newton matrix).
#include <memory>
#include <vector>

#include <tbb/task_arena.h>

#include "solver/batch/host_environments.hpp"

namespace grip::solver {

// The CPU engine: its environments (solver::Environment) stepped on a TBB arena.
class Batch final : public HostEnvironments {
 public:
  // threads = 0: all the machine's cores.
  explicit Batch(int threads = 0);

  // Adds an environment of `model` under the batch's policy and returns its index.
  int add(std::shared_ptr<const Model> model) override;
  int threads() const override { return threads_; }

  // The step policy of every environment, present and future (StepPolicy). By default an
  // environment whose Newton converged is frozen for the rest of the step; without
  // freeze_converged every environment keeps iterating until all have converged (one global
  // convergence test, as a monolithic solver of all environments would have).
  void set_policy(const StepPolicy& policy) override;

  // One time step (each environment's own dt) of every active environment.
  BatchStepReport step() override;

 private:
  int threads_;
  tbb::task_arena arena_;
  StepPolicy policy_;
};

}  // namespace grip::solver
