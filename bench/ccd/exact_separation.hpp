#pragma once
// Exact checks of a CCD query's pair: still apart at a given time, or touching at t = 0 as
// stored (rational); squared distances in rational arithmetic (CGAL), with no round-off.
#include "bench/ccd/ccd_query.hpp"

namespace grip::bench {

// True when the closed primitives of `query` at time t (vertices x0 + t (x1 - x0), all values
// taken as the exact rationals of their doubles) are farther apart than min_separation.
bool exactly_separated_at(const CcdQuery& query, CcdQueryType type, double t,
                          double min_separation);

// True when the closed primitives of the rational query touch (distance exactly 0) at t = 0.
bool exactly_touching_at_start(const RationalCcdQuery& query, CcdQueryType type);

}  // namespace grip::bench
