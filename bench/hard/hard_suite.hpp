#pragma once
// Runs hard cases and checks, after every accepted step and independently of the solver, the
// invariants IPC promises (no intersection: exact predicates; no inverted tet: det F > 0), the
// solver's outcome and each case's physical check, with per-step statistics.
#include <string>
#include <vector>

#include "bench/hard/hard_case.hpp"

namespace grip::bench {

// The exact invariants of one state.
struct InvariantCheck {
  int intersections = 0;          // intersecting (edge, triangle) pairs of bodies that may touch
  double min_volume_ratio = 1.0;  // smallest det F over all tets
  bool holds() const { return intersections == 0 && min_volume_ratio > 0.0; }
};
InvariantCheck check_invariants(const solver::Environment& env);

struct HardStep {
  int newton_iterations = 0;
  int line_search_steps = 0;
  double min_distance = 0.0;  // over pairs within d_hat; infinite when none
  double min_volume_ratio = 1.0;
};

struct HardCaseResult {
  std::string name;
  std::string challenge;
  double d_hat = 0.0;
  int planned_steps = 0;
  std::vector<HardStep> steps;  // one per accepted step
  int intersecting_steps = 0;   // accepted steps after which surfaces intersected
  int inverted_steps = 0;       // accepted steps after which a tet had det F <= 0
  bool failure_expected = false;
  std::string solver_failure;    // the solver's reason; empty when it ran every step
  std::string physical_failure;  // the first broken physical check; empty when none
  double solve_seconds = 0.0;    // in the solver's steps only
  double check_seconds = 0.0;    // in the checks

  bool intersection_free() const { return intersecting_steps == 0; }
  bool inversion_free() const { return inverted_steps == 0; }
  // The solver failed exactly when the case expects it to.
  bool outcome_as_expected() const { return solver_failure.empty() != failure_expected; }
  bool passed() const {
    return intersection_free() && inversion_free() && outcome_as_expected() &&
           physical_failure.empty();
  }
  double newton_mean() const;
  int newton_max() const;
  long line_search_total() const;
  double min_distance_over_d_hat() const;  // infinite when nothing came within d_hat
  double min_volume_ratio() const;
};

// Runs one case for its steps (or until the solver fails).
HardCaseResult run_hard_case(const HardCase& hard_case);

// Runs the cases side by side on `threads` threads (0: all cores), one case per task; each
// case's result is the same whatever the thread count (the solver's arithmetic does not depend
// on it), except for the wall times.
std::vector<HardCaseResult> run_hard_cases(const std::vector<HardCase>& cases, int threads);

}  // namespace grip::bench
