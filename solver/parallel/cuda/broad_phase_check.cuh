#pragma once
// The device check's broad phase (grip-gpu-check, broad_phase_check.cu): per environment two
// sheets of 2 mm triangles facing each other 0.4 to 1.4 mm apart, the upper one rippled and
// closing by 0.3 mm on its path, the lower one among untouching bodies (so edge pairs are
// listed from its side), with d_hat = 1 mm: pairs between the sheets and of the upper sheet
// with itself, then the reach filter over them (CCD rescaling 0.1), then the friction lag with
// the upper sheets raised 0.5 mm off their start (kappa = 1 kN/m). The candidates, both of the
// filter's lists and the lagged contacts' vertices found on the device must equal the host
// launcher's exactly (the mollifier thresholds to round-off), the contacts' mu lambda and
// tangent-plane projectors to round-off.
#include <string>

namespace grip::solver::parallel {

struct BroadPhaseCheck {
  double device_ms = 0.0, host_ms = 0.0, bytes = 0.0;
  int pairs = 0;                   // candidates, on the host
  int reachable = 0, watched = 0;  // within reach; watched by CCD (host)
  bool identical = false;      // every array of the device's candidates and lists equals the host's
  std::string mismatch;        // else the first that differs
  int lagged = 0;              // friction contacts (host)
  bool lag_identical = false;  // their vertices and environments, device and host
  double lag_difference = 0.0;  // their mu lambda and T T^T's largest relative difference
};

BroadPhaseCheck check_broad_phase(int environments, int repeats);

}  // namespace grip::solver::parallel
