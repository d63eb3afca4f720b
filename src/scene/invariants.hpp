#pragma once
// The exact invariant a simulated environment must keep after every accepted step: its
// collision surfaces do not intersect (checked with exact predicates, independently of the
// solver's own distance bookkeeping).
#include "solver/environment.hpp"

namespace grip::scene {

// The number of (edge, triangle) pairs of bodies that may touch which intersect now.
int count_intersections(const solver::Environment& environment);

}  // namespace grip::scene
