#pragma once
// What an environment reports about its steps: the last step's diagnostics (Newton and line
// search counts, closest contact, worst tet, contact forces per pair of bodies) and totals.
#include <chrono>
#include <cstddef>
#include <limits>
#include <vector>

#include "solver/potential/contact_forces.hpp"

namespace grip::solver {

struct StepDiagnostics {
  int newton_iterations = 0;  // over all its parts when the step was retried in halves
  int retries = 0;            // parts of the step rolled back and retried as two halves
  int line_search_steps = 0;  // Armijo halvings and inversion halvings
  // Over the barrier's pairs within d_hat (not an FEM body's pairs within d_hat at rest).
  double min_distance = std::numeric_limits<double>::infinity();
  double min_volume_ratio = 1.0;  // smallest det F over all tets (1 without FEM)
  double kappa = 0.0;
  int friction_contacts = 0;  // lagged friction contacts of the last lag
  // The infinity norm of the free DOFs' gradient at the end, scaled by 1/h^2 (N).
  double residual = 0.0;
  std::vector<PairForce> contact_forces;
};

// Where an environment's time went (wall seconds, summed over its steps), by stage of Newton's
// iteration. The broad phase is the candidate search of assembly and of the line search's CCD;
// the friction lag and the end-of-step diagnostics include their own candidate searches.
struct StageSeconds {
  double broad_phase = 0.0;
  double derivatives = 0.0;    // energy derivatives of every term, PSD projection included
  double assembly = 0.0;       // pinned DOFs eliminated, triplets summed into the matrix
  double factorization = 0.0;  // numeric (and, when the pattern changes, symbolic)
  double solve = 0.0;          // triangular solves
  double ccd = 0.0;            // the collision-free fraction of the step
  double line_search = 0.0;    // inversion halvings and Armijo's energy evaluations
  double friction_lag = 0.0;
  double diagnostics = 0.0;  // contact forces and closest distance at the end of a step

  double total() const {
    return broad_phase + derivatives + assembly + factorization + solve + ccd + line_search +
           friction_lag + diagnostics;
  }
};

// How an environment's Newton systems were solved (NewtonSolver::solve): by a fresh
// factorization, or by CG preconditioned with an earlier iteration's factorization.
struct LinearSolveCounts {
  long factorizations = 0;  // numeric factorizations (failed ones included)
  long reused = 0;          // systems CG solved on an earlier factorization
  long cg_iterations = 0;   // CG iterations, those that ended in a factorization included
};

// Adds the wall time from its construction to its destruction to `seconds`.
class StageTimer {
 public:
  explicit StageTimer(double& seconds)
      : seconds_(seconds), start_(std::chrono::steady_clock::now()) {}
  ~StageTimer() {
    seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  StageTimer(const StageTimer&) = delete;
  StageTimer& operator=(const StageTimer&) = delete;

 private:
  double& seconds_;
  std::chrono::steady_clock::time_point start_;
};

// Totals over every step an environment has taken.
struct EnvironmentStatistics {
  long steps = 0;
  long newton_iterations = 0;
  int max_step_iterations = 0;  // most Newton iterations in one step (all its parts)
  long retries = 0;             // failed steps (or parts) retried as two half steps
  // steps_by_iterations[n]: how many steps took n Newton iterations (all their parts). The
  // step a failure gave up on counts too: a stall is what this histogram is for.
  std::vector<long> steps_by_iterations;

  void count_step(int iterations) {
    const auto n = static_cast<std::size_t>(iterations);
    if (steps_by_iterations.size() <= n) steps_by_iterations.resize(n + 1, 0);
    ++steps_by_iterations[n];
  }
};

}  // namespace grip::solver
