#pragma once
// A generated set of hard CCD queries with answers known by construction: contact exactly at
// t = 1, touching at t = 0 (on a face, an edge or a vertex, crossing or collinear edges) while
// moving apart, along or through, a point through an edge or a vertex, collinear edges, parallel
// edges, zero relative motion, misses and hits by 2^-40 (~1e-12), fast motion, at scales
// 2^-20 (~1e-6), 1 and 2^13 (~1e4), in several axis permutations, with exact rational
// coordinates (dyadic wherever contact is exact, so rounding to double keeps the answer).
#include <vector>

#include "bench/ccd/ccd_query.hpp"

namespace grip::bench {

std::vector<RationalCcdQuery> hard_ccd_queries(CcdQueryType type);

}  // namespace grip::bench
