#pragma once
// The exact invariant a simulated environment must keep after every accepted step: its
// collision surfaces do not intersect (checked with exact predicates, independently of the
// solver's own distance bookkeeping).
#include <optional>
#include <utility>

#include "solver/engine/engine.hpp"

namespace grip::scene {

// The number of (edge, triangle) pairs of bodies that may touch which intersect now.
int count_intersections(const solver::EnvironmentHandle& environment);

// A body that lies wholly inside another's closed surface (every collision vertex inside it, by
// the exact signed distance), of a pair that may touch: no surfaces cross, so neither
// count_intersections nor the solver sees it. Returns (inner, outer), the first such pair.
std::optional<std::pair<int, int>> find_contained_body(
    const solver::EnvironmentHandle& environment);

}  // namespace grip::scene
