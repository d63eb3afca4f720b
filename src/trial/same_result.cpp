#include "src/trial/same_result.hpp"

#include <cmath>

namespace grip::trial {

bool same_result(const io::CandidateResult& a, const io::CandidateResult& b) {
  io::CandidateResult x = a, y = b;
  x.record.wall_time = y.record.wall_time = 0.0;
  auto same_nan = [](double& dx, double& dy) {
    if (std::isnan(dx) && std::isnan(dy)) dx = dy = 0.0;
  };
  for (std::size_t k = 0; k < x.record.displacement.size(); ++k) {
    same_nan(x.record.displacement[k], y.record.displacement[k]);
    same_nan(x.record.phase_seconds[k], y.record.phase_seconds[k]);
  }
  same_nan(x.record.d1, y.record.d1);
  same_nan(x.record.d2, y.record.d2);
  return x.record == y.record && x.trajectory == y.trajectory && x.stress == y.stress &&
         x.finger_stress == y.finger_stress;
}

}  // namespace grip::trial
