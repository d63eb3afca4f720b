#pragma once
// `grip bench peer`: the GRIP paper's simulator comparison (Table I: IPC against Isaac Gym)
// reproduced against MuJoCo. The same synthesized parallel-jaw, fin-ray or LEAP-hand candidates
// on rigid objects run through grip's trial and through the same scene in MuJoCo
// (mujoco_trial.hpp, mujoco_hand_trial.hpp); per engine the verdict, D1/D2 at its settled grasp
// (measured by the same code) and the CPU time, and MuJoCo's deepest contact and inverted tets.
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "src/trial/trial_parameters.hpp"

namespace grip::bench {

// The default categories: six on which the parallel jaws and the hand find candidates.
inline const std::vector<std::string> kPeerCategories = {"box",    "cylinder", "capsule",
                                                         "bottle", "sphere",   "ellipsoid"};
// The grippers compared: the rigid parallel jaws, the fin-ray (its production fingers; MuJoCo's
// are flexes of the same tets) and the LEAP hand (its coarse links, as `grip bench robustness`
// simulates it).
inline const std::vector<std::string> kPeerGrippers = {"parallel-jaw", "fin-ray", "leap"};

struct PeerOptions {
  std::string gripper = "parallel-jaw";  // one of kPeerGrippers
  std::vector<std::string> categories;   // empty: kPeerCategories
  int seeds = 4;                         // shapes per category
  int candidates = 9;                    // per shape
  int threads = 1;                       // grip's trial; MuJoCo runs on one
  trial::TrialParameters parameters;
  std::filesystem::path out = "out/peer";
  // If set, the first candidate of each kind of disagreement as VTK here (peer_vtk.hpp): the
  // hand's and the fin-ray's.
  std::filesystem::path vtk;
  // The fin-ray's MuJoCo scenes with MuJoCo's experimental IPC contact mode (MujocoSettings::ipc).
  bool mujoco_ipc = false;
};

// One candidate through both engines.
struct PeerTrial {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  std::string gripper;
  std::string category;
  std::uint64_t seed = 0;
  std::uint64_t candidate = 0;
  // grip: "success" or its failure kind; D1/D2 at the settled grasp (NaN if none).
  std::string grip_verdict;
  double grip_d1 = nan, grip_d2 = nan;
  double grip_slip = nan;  // m, the largest over the gravity phases run
  double grip_cpu_seconds = 0.0;
  // MuJoCo: the same.
  std::string mujoco_verdict;
  std::string mujoco_message;
  double mujoco_d1 = nan, mujoco_d2 = nan;
  double mujoco_slip = nan;
  // MuJoCo's deepest contact between object and gripper at any step (m), and the most of a soft
  // finger's tets it inverted at once (grip's: none, by construction).
  double mujoco_penetration = 0.0;
  int mujoco_inverted_tets = 0;
  double mujoco_cpu_seconds = 0.0;
  double mujoco_compile_cpu_seconds = 0.0;  // building the model, not counted in the above
};

// grip refused the candidate (its pose intersects the object): not simulated, not compared.
bool refused_by_grip(const PeerTrial& trial);

struct PeerResult {
  std::string gripper;
  std::vector<PeerTrial> trials;
  std::vector<std::string> skipped;     // "box seed 3": no candidate on that shape
  std::vector<std::string> shortfalls;  // fewer shapes or candidates than asked
  std::vector<std::string> vtk;         // the VTK series written, "STEM: why"
  std::string mujoco_version;
  bool mujoco_ipc = false;  // PeerOptions'
  int threads = 0;
  trial::TrialParameters parameters;
  double wall_seconds = 0.0;
};

// Throws std::invalid_argument for an unknown gripper or category, seeds or candidates below 1,
// or mujoco_ipc for a gripper other than the fin-ray.
void check_peer_options(const PeerOptions& options);

// Requires MuJoCo (mujoco_available()). Logs one line per shape.
PeerResult run_peer(const PeerOptions& options);

}  // namespace grip::bench
