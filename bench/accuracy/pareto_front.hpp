#pragma once
// The Pareto front of settings measured by cost (wall time) and error: the settings that no
// other setting beats on both at once.
#include <vector>

namespace grip::bench {

struct CostError {
  double cost = 0;
  double error = 0;
};

// Per point, whether it is on the front: no other point costs no more and errs no more, and
// strictly less on one of the two. A point whose cost or error is NaN is never on it and
// dominates none.
std::vector<bool> pareto_front(const std::vector<CostError>& points);

}  // namespace grip::bench
