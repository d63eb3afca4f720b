#pragma once
// Exact check that a CCD query's pair is still apart at a given time: positions and squared
// distance evaluated in rational arithmetic (CGAL), so the answer carries no round-off.
#include "bench/ccd/ccd_query.hpp"

namespace grip::bench {

// True when the closed primitives of `query` at time t (vertices x0 + t (x1 - x0), all values
// taken as the exact rationals of their doubles) are farther apart than min_separation.
bool exactly_separated_at(const CcdQuery& query, CcdQueryType type, double t,
                          double min_separation);

}  // namespace grip::bench
