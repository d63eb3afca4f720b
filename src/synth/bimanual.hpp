#pragma once
// Bimanual composition (GRIP paper, Sec. III-C): k-means of the right and left candidates on
// their contact centres, the r1 k^2 cluster pairs whose centres lie farthest apart, all
// combinations within them, and per pair the best fraction by an approximate force-closure
// metric over both hands' contacts; pairs whose hands come too close are discarded.
#include <cstdint>
#include <functional>
#include <vector>

#include "src/geometry/mesh.hpp"
#include "src/synth/candidate.hpp"
#include "src/synth/prepared_object.hpp"

namespace grip::synth {

struct BimanualParams {
  int clusters = 26;               // k
  double pair_fraction = 0.25;     // r1
  double hand_clearance = 1.5e-3;  // m, exact distance the two hands keep (d_hat + margin)
};

struct BimanualStatistics {
  std::int64_t filtered = 0;   // n_filtered: combinations in the selected cluster pairs
  std::int64_t examined = 0;   // combinations checked for hand-hand clearance
  std::int64_t colliding = 0;  // of which the hands came too close
};

// `right` and `left` are unimanual candidates of one gripper kind (one hand each); `posed`
// gives the world surface of a one-hand candidate and whether it is the left one. Returns up to
// about `target` two-hand candidates (right first), energies: fc_bimanual (force-closure error
// over both hands' contacts, torques about the object centroid), then the right and left
// hands' own terms prefixed right_ and left_. Each selected pair keeps its best
// ceil(r2 m) of m combinations, r2 = target / n_filtered (colliding ones do not count), pairs
// taken farthest first until `target` candidates are kept.
std::vector<Candidate> compose_bimanual(
    const PreparedObject& object, const std::vector<Candidate>& right,
    const std::vector<Candidate>& left, int target, const BimanualParams& params,
    std::uint64_t seed,
    const std::function<geometry::SurfaceMesh(const Candidate&, bool left)>& posed,
    BimanualStatistics* statistics = nullptr);

}  // namespace grip::synth
