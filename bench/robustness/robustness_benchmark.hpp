#pragma once
// `grip bench robustness`: how often the solver fails on ordinary grasps. Candidates are
// synthesized on every procedural object category for several seeds and three grippers, and
// their trials run through the real protocol, one solver::Batch per (object, gripper).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "io/candidate_record.hpp"
#include "src/geometry/tetrahedralize.hpp"
#include "src/trial/trial_parameters.hpp"

namespace grip::bench {

struct RobustnessOptions {
  std::vector<std::string> grippers;    // parallel-jaw, fin-ray, leap; empty: all three
  std::vector<std::string> categories;  // procedural categories; empty: every one
  int seeds = 0;                        // shapes per category; 0: each gripper's default
  int candidates = 0;                   // per (object, gripper); 0: each gripper's default
  bool rigid = true;                    // run rigid objects (one affine body)
  bool soft = true;                     // run soft objects (FEM, as `grip trial --soft`)
  // The models `grip trial` and the farm simulate (the 4-layer fin-ray finger, the shipped LEAP
  // hand, `grip trial --soft`'s tets); false: the coarse ones (robustness_gripper_model).
  bool production_models = false;
  // The production soft objects' interior growth (geometry::TetOptions::interior_growth), as
  // `grip trial --soft` meshes them by default.
  double soft_interior_growth = geometry::kSoftObjectInteriorGrowth;
  // The fin-ray finger meshed finer than production's (kFineFinRay: grip bench labels
  // --refine finger); with production models only.
  bool fine_fin_ray = false;
  trial::TrialParameters parameters;  // the protocol and the solver's settings
  // Run decided trials to the end (trial::TrialRunOptions::full_trials): the same verdicts.
  bool full_trials = false;
  int threads = 0;  // 0: all cores
  std::filesystem::path out = "out/robustness";
};

// What the options ask of one gripper, category and object model: `seeds` shapes, the first
// seeds (1, 2, 3, ...) for which synthesis finds a candidate (a shape wider than the gripper
// opens gives none and is skipped), and `candidates` trials on each.
struct RobustnessSet {
  std::string gripper;  // registry name
  std::string category;
  bool soft = false;
  int seeds = 0;
  int candidates = 0;
  bool production_models = false;  // RobustnessOptions::production_models
  double soft_interior_growth = geometry::kSoftObjectInteriorGrowth;  // RobustnessOptions's
  bool fine_fin_ray = false;                                          // RobustnessOptions's
};

// At most this many seeds are tried per shape asked for.
inline constexpr int kSeedsTriedPerShape = 10;

// One (object, gripper) batch that ran.
struct RobustnessBatch {
  std::string gripper;
  std::string category;
  std::uint64_t seed = 0;  // the shape's and the synthesis's seed, as `grip synth --seed`
  bool soft = false;
  int candidates = 0;  // synthesized and run (at most the set's)
};

// The finer fin-ray finger's mesh: 8 tet layers, profile edges up to 4 mm (production: 4 and
// 6 mm), 4.5x production's tets (docs/assets.md, "The fin-ray finger's mesh").
inline constexpr int kFineFinRayLayers = 8;
inline constexpr double kFineFinRayEdge = 0.004;  // m

// The finer fin-ray finger, in words, against production's: "8 tet layers and 4 mm profile
// edges (production: 4 and 6 mm)".
std::string fine_fin_ray_model();

// The gripper each registry name is simulated with in this benchmark, in words.
std::string robustness_gripper_model(const std::string& gripper, bool production_models);

// The categories `categories` names: every category of the object library when it is empty.
std::vector<std::string> robustness_categories(const std::vector<std::string>& categories);

// The sets the options ask for: gripper by gripper, then category, rigid before soft. Throws
// std::invalid_argument for an unknown gripper or category, seeds or candidates below 0, or
// neither rigid nor soft objects; the message leaves naming the command to its caller.
std::vector<RobustnessSet> plan_robustness(const RobustnessOptions& options);

struct RobustnessTrial {
  std::string gripper;
  std::string category;
  std::uint64_t seed = 0;
  bool soft = false;
  std::uint64_t candidate = 0;  // index in the batch's synthesized candidates
  io::Status status = io::Status::kPending;
  io::FailureKind failure = io::FailureKind::kNone;
  std::string failure_reason;  // the solver's message when it failed
  io::NewtonStatistics newton;
  std::vector<long> steps_by_iterations;  // [n]: steps with n Newton iterations, failed one too
  std::vector<double> closing_forces;     // N per finger, at the end of closing
  bool closed = false;                    // closing ended (trial::TrialOutcome::closed)
  double settle_displacement = 0.0;       // m; NaN if it did not settle
  double largest_slip = 0.0;  // m, the verdict's, over the gravity phases run; NaN if none
  // The largest slip over the verdict's threshold at a phase's end (trial::slip_over_threshold):
  // at least 1 if it slipped; NaN if no gravity phase ran.
  double largest_slip_ratio = 0.0;
  double largest_center_displacement = 0.0;  // m, the centre of mass's (sag and slip); NaN if none
  double largest_end_speed = 0.0;  // m/s, trial::TrialOutcome::end_speed's largest; NaN if none
  double gravity_seconds = 0.0;    // s, the gravity phases' time together (phase_seconds' sum)
};

// "success" or the trial's failure kind.
std::string verdict_of(const RobustnessTrial& trial);

struct RobustnessResult {
  std::vector<RobustnessSet> sets;       // the plan
  std::vector<RobustnessBatch> batches;  // what ran, in order
  std::vector<RobustnessTrial> trials;   // batch by batch, candidates in order
  // "parallel-jaw x box seed 1 rigid": seeds whose shape got no candidate, so no batch.
  std::vector<std::string> skipped;
  // Sets that got fewer shapes or candidates than asked, and batches whose object could not be
  // prepared or run, in words.
  std::vector<std::string> shortfalls;
  int threads = 0;
  double wall_seconds = 0.0;
};

// Runs the planned sets on options.threads threads: per gripper and category, seed by seed,
// synthesis, object preparation and the trials. Logs one line per batch. Deterministic for
// given options, whatever the thread count.
RobustnessResult run_robustness(const RobustnessOptions& options);

}  // namespace grip::bench
