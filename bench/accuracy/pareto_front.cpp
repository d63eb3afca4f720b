#include "bench/accuracy/pareto_front.hpp"

#include <cmath>

namespace grip::bench {

std::vector<bool> pareto_front(const std::vector<CostError>& points) {
  const auto valid = [](const CostError& p) { return !std::isnan(p.cost) && !std::isnan(p.error); };
  std::vector<bool> front(points.size(), false);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!valid(points[i])) continue;
    front[i] = true;
    for (std::size_t j = 0; j < points.size() && front[i]; ++j) {
      const CostError &a = points[j], &b = points[i];
      if (j == i || !valid(a)) continue;
      front[i] =
          !(a.cost <= b.cost && a.error <= b.error && (a.cost < b.cost || a.error < b.error));
    }
  }
  return front;
}

}  // namespace grip::bench
