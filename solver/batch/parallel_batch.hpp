#pragma once
// The data-parallel engine's time step (GRIP, Section III-A): every environment of a batch
// stepped at once over the flat buffers of solver/parallel/, on a host launcher, as the CPU
// engine's Environment steps one (solver/environment.cpp):
// - a part of length dt / 2^halvings begins with its targets (the scripts advanced, the
//   driven bodies' drive targets, the pins' targets), the step's constants
//   (step_start_stages.hpp), the barrier's pairs within d_hat of its start and the friction
//   lagged there (step_contacts.hpp);
// - Newton iterations (newton_iteration.hpp) run in rounds over every environment still
//   iterating; a converged solve is followed by the next friction lag
//   (SimParameters::friction_lag_iterations) or ends the part;
// - a part that fails, or whose solve reaches max_newton_iters, is rolled back and retried as
//   two halves, at most max_step_halvings deep, before the environment fails with the code
//   the CPU engine gives;
// - a part ends with the velocities (q - q_start) / h and the scripted bodies at their
//   targets; the step ends with the clock at its end, the closest contact, the contact forces
//   per pair of bodies and the worst tet, and kappa doubled where adaptive kappa asks for it.
// Each environment's state lives in the caller's State between steps; the batch copies it into
// its buffers at a part's start and back at the part's end. An environment's result does not
// depend on the others of the batch.
#include <memory>
#include <string>
#include <vector>

#include "solver/model/model.hpp"
#include "solver/newton/diagnostics.hpp"
#include "solver/newton/failure.hpp"
#include "solver/newton/step_policy.hpp"
#include "solver/potential/friction_term.hpp"
#include "solver/scene/state.hpp"

namespace grip::solver {

// What a step did to one environment. Its diagnostics are the CPU engine's but for the line
// search's halvings, which it leaves at zero.
struct ParallelStepResult {
  bool stepped = false;  // it took part in the step
  Failure failure = Failure::kNone;
  std::string message;  // why it failed, for people
  StepDiagnostics diagnostics;
  long cg_iterations = 0;  // over every Newton iteration of the step
  // The contacts its potential ended with (Environment::AdoptedStep): the collision vertices at
  // its last part's start, that part's length, the barrier stiffness and the last friction lag.
  Vertices start_positions;
  double h = 0.0;
  double kappa = 0.0;
  std::vector<FrictionContact> friction;
};

class ParallelBatch {
 public:
  // One environment per model (models may repeat). threads: 0 all the machine's cores, 1 the
  // serial launcher. The models must share ccd_rescaling (one for the batch).
  explicit ParallelBatch(std::vector<std::shared_ptr<const Model>> models, int threads = 0);
  ~ParallelBatch();
  ParallelBatch(const ParallelBatch&) = delete;
  ParallelBatch& operator=(const ParallelBatch&) = delete;

  int size() const;
  // Rounds of Newton iterations the last step took (each over every environment still
  // iterating).
  int rounds() const;

  // One step of dt (each environment's own) of the environments `stepping` marks, from and into
  // states[e]; the others' states are read, not changed. The states must be free of
  // intersections (Environment checks a scene's start). Steps held open
  // (StepPolicy::freeze_converged off) are not supported: std::invalid_argument.
  std::vector<ParallelStepResult> step(std::vector<State>& states,
                                       const std::vector<unsigned char>& stepping,
                                       const StepPolicy& policy = {});

  struct Buffers;

 private:
  std::unique_ptr<Buffers> buffers_;
};

}  // namespace grip::solver
