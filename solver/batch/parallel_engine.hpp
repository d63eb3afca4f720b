#pragma once
// The data-parallel engine behind the seam (solver/engine/engine.hpp): every active
// environment stepped at once by a ParallelBatch (its flat buffers, a host launcher), with a
// CPU Environment per environment as its host handle. Between steps the caller places bodies,
// sets scripts and gravity and reads results through the handle, on the host; a step copies each
// active environment's state into the batch and hands back what the step left
// (Environment::adopt_step). The batch is built again when the active environments change (an
// environment added, retired or failed): an environment's step does not depend on the others.
//
// It differs from the CPU engine (solver::Batch) by the linear solver (dense Cholesky for small
// rigid systems, CG otherwise, not CHOLMOD; a solver attached with use_linear_solver is not
// used), by stage_seconds (zero: the batch does not time environments one by one) and by steps
// held open (StepPolicy::freeze_converged off), which it refuses with std::invalid_argument.
#include <memory>
#include <vector>

#include "solver/batch/host_environments.hpp"
#include "solver/batch/parallel_batch.hpp"

namespace grip::solver {

class ParallelEngine final : public HostEnvironments {
 public:
  // threads = 0: all the machine's cores; 1: the serial launcher.
  explicit ParallelEngine(int threads = 0);
  ~ParallelEngine() override;

  int add(std::shared_ptr<const Model> model) override;
  int threads() const override { return threads_; }

  void set_policy(const StepPolicy& policy) override { policy_ = policy; }
  BatchStepReport step() override;

 private:
  int threads_;
  std::vector<std::shared_ptr<const Model>> models_;  // per environment
  StepPolicy policy_;
  std::vector<int> members_;  // the environments batch_ was built of, in its order
  std::unique_ptr<ParallelBatch> batch_;
};

}  // namespace grip::solver
