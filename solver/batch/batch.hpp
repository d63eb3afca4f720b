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

#include "solver/environment.hpp"

namespace grip::solver {

// What one batch step cost: rounds of Newton iterations, and per round how many environments
// iterated and how many sat frozen (converged this step, while others still iterated).
struct BatchStepReport {
  int stepped = 0;  // environments that took part in the step
  int rounds = 0;
  long iterations = 0;  // environment-iterations over all rounds
  long frozen = 0;      // environment-rounds spent frozen
  int failed = 0;       // environments that failed in this step
};

class Batch {
 public:
  // threads = 0: all the machine's cores.
  explicit Batch(int threads = 0);

  // Adds an environment of `model` and returns its index. Take it with environment(i) to place
  // bodies, set gravity and scripts between steps.
  int add(std::shared_ptr<const Model> model);
  Environment& environment(int index) { return *environments_.at(static_cast<std::size_t>(index)); }
  const Environment& environment(int index) const {
    return *environments_.at(static_cast<std::size_t>(index));
  }
  int size() const { return static_cast<int>(environments_.size()); }
  int threads() const { return threads_; }

  // Takes an environment out of further steps (its trial is over); it keeps its state.
  void retire(int index) { active_.at(static_cast<std::size_t>(index)) = 0; }
  // Not retired and not failed.
  bool active(int index) const;
  bool any_active() const;

  // The step policy of every environment, present and future (StepPolicy). By default an
  // environment whose Newton converged is frozen for the rest of the step; without
  // freeze_converged every environment keeps iterating until all have converged (one global
  // convergence test, as a monolithic solver of all environments would have).
  void set_policy(const StepPolicy& policy);

  // One time step (each environment's own dt) of every active environment.
  BatchStepReport step();

 private:
  int threads_;
  tbb::task_arena arena_;
  std::vector<std::unique_ptr<Environment>> environments_;
  std::vector<char> active_;
  StepPolicy policy_;
};

}  // namespace grip::solver
