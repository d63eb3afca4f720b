#pragma once
// What `grip bench peer` reports: per gripper and category (and over all categories) each
// engine's D1/D2 over the grasps it holds, the verdicts' agreement and the two kinds of
// disagreement, MuJoCo's deepest contact and inverted tets, and CPU time per trial; as a text
// table, peer.md, peer.csv (one row per candidate; peer-GRIPPER.* for the fin-ray and the hand)
// and one JSON line.
#include <filesystem>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "bench/peer/peer_benchmark.hpp"

namespace grip::bench {

// One engine over a set of candidates; NaN where nothing was measured.
struct PeerEngineStats {
  int held = 0;
  double d1_mean = 0.0, d1_median = 0.0;    // m, over the held grasps
  double d2_mean = 0.0, d2_median = 0.0;    // m
  double cpu_mean = 0.0, cpu_median = 0.0;  // s per trial, over the compared candidates
  std::map<std::string, int> verdicts;      // verdict -> count, over the compared candidates
};

struct PeerTally {
  std::string gripper;
  std::string category;  // "all" for every category
  int candidates = 0;
  int refused = 0;      // grip's initial_penetration: not simulated by grip, not compared
  int compared = 0;     // the others
  int agree = 0;        // both hold or both drop
  int mujoco_only = 0;  // MuJoCo holds what grip drops
  int grip_only = 0;    // grip holds what MuJoCo drops
  PeerEngineStats grip, mujoco;
  // MuJoCo's deepest contact at any step of a trial (m): median and largest over the compared
  // candidates; and how many of them inverted a soft finger's tet (grip's never do).
  double mujoco_penetration_median = 0.0, mujoco_penetration_max = 0.0;
  int mujoco_inverting = 0;
};

// Per gripper: its categories in the order run, then "all".
std::vector<PeerTally> peer_tallies(const PeerResult& result);

void write_peer_table(std::ostream& out, const std::vector<PeerTally>& tallies);
// The files' name without extension: "peer" for the parallel jaws (the first gripper
// compared), "peer-GRIPPER" for another.
std::string peer_file_stem(const std::string& gripper);

// STEM.md (settings, tables) and STEM.csv in `out` (created if missing), STEM =
// peer_file_stem(result.gripper).
void write_peer_files(const std::filesystem::path& out, const PeerResult& result,
                      const std::vector<PeerTally>& tallies);
void write_peer_json_line(std::ostream& out, const PeerResult& result,
                          const std::vector<PeerTally>& tallies);

}  // namespace grip::bench
